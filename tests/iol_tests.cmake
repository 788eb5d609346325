# The intraocular-lens scenes (prm/iol): the lens mesh, the compression
# tests and their references. Label iol.
set(CHECK_HAPTIC ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_haptic.py)

# coshell_iol_test(NAME CHECKER PRM checker arguments...): runs
# tests/scripts/CHECKER on prm/iol/PRM into output/NAME, label iol.
function(coshell_iol_test name checker prm)
  add_test(NAME ${name}
           COMMAND ${COSHELL_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/scripts/${checker}
                   --coshell $<TARGET_FILE:coshell>
                   --prm ${COSHELL_PRM}/iol/${prm}
                   --output ${CMAKE_CURRENT_BINARY_DIR}/output/${name}
                   ${ARGN})
  set_tests_properties(${name} PROPERTIES LABELS iol)
endfunction()

# One C-loop haptic clamped at its root and pushed at its tip towards the
# lens centre (0.01 mN, linear): tip stiffness against Castigliano's
# curved-beam solution, 2.3843e-5 N/mm (bending E t w^3 / 12 plus axial
# and shear). ANDES: 6.5 %, 2.2 %, 0.5 % stiffer on 182, 736, 3064
# triangles; the finest level is asserted within 1 % (the issue asks 3 %).
# CST locks in this in-plane bending: 1.54 times too stiff on the coarse
# mesh (two triangles across the haptic), asserted above 1.4 times.
function(coshell_haptic_test name membrane)
  coshell_iol_test(${name} check_haptic.py haptic_compression.prm
                   --set "Element/Membrane element=${membrane}"
                   --set ${no_vtu} ${ARGN})
endfunction()
coshell_haptic_test(iol.haptic_compression.andes andes --rtol 0.01)
coshell_haptic_test(iol.haptic_compression.cst cst --stiffer-than 1.4)
# One modified-L haptic (lens.geo haptic_type = 1: a straight leg from the
# optic rim, a 90-degree knee of 0.6 mm centre-line radius, an arm of
# 4.5 mm radius to 15 degrees past its farthest point), clamped at the
# rim, 0.01 mN at its tip towards the lens centre; the checker sets the
# mesh, the load and the tip from the same geometry. Castigliano on the
# leg, knee and arm: 2.1774e-5 N/mm. ANDES's finest level (3 refinements
# of 0.22 mm) is asserted within 1 %.
coshell_haptic_test(iol.haptic_compression.modified_l.andes andes
                    --haptic-type 1 --rtol 0.01)

# The whole lens between two concave clamps closing from 13.1 to 10 mm
# (ISO 11979-3): the barrier's gap stays non-negative at every step, the
# two clamp forces balance within 1 % (quasi-static equilibrium), the
# force grows with the compression and ends finite and positive.
# The force curve is written to compression.csv (mN against mm) and
# drawn, as doc/validation/iol/compression.png, into
# build/tests/output/iol.compression_iso11979/compression.png.
coshell_iol_test(iol.compression_iso11979 check_compression.py
                 compression_iso11979.prm --set ${no_vtu}
                 --plot ${CMAKE_CURRENT_BINARY_DIR}/output/iol.compression_iso11979/compression.png)
# The same with Linear solver/Reuse factorization: the same assertions,
# and some solves used kept factors (UMFPACK's: the consistent tangent is
# not symmetric). A solver that ignored the request would fail here.
coshell_iol_test(iol.compression_iso11979.kept_factors check_compression.py
                 compression_iso11979.prm --set ${no_vtu}
                 --set "Linear solver/Reuse factorization=true"
                 --kept-factors-used)
# The modified-L lens (lens.geo haptic_type = 1) in the same clamps: no
# interpenetration, the clamp forces balance within 1 % (measured 0.06 %)
# and end finite and positive. Its arms, loaded at their farthest points,
# turn the lens and it buckles out of its plane: the force peaks, first
# drops and then stays near its peak down to 10 mm, with the optic vaulted
# (doc/validation.md gives the values).
# Regression guard (label regression): that the buckle starts between
# 10.95 and 10.80 mm pins this code's own earlier run, not a validation:
# there is no measured curve to compare.
coshell_iol_test(iol.compression_iso11979.modified_l check_compression.py
                 compression_iso11979.prm --set ${no_vtu}
                 --set "Mesh/Gmsh parameters=haptic_type = 1"
                 --buckle-between 10.95 10.80)
set_tests_properties(iol.compression_iso11979.modified_l
  PROPERTIES LABELS "iol;regression")

# The lens on the test chamber's floor instead of its optic's rotations
# held: a rigid plane (meshes/contact/plane.geo) 0.02 mm under the optic's
# lowest point, frictionless, and the lens's weight in saline, gravity
# 9810 * (1 - 1.0 / 1.2) = 1635 mm/s^2 along -z; no lens node is
# constrained. The same assertions, and at every step the obstacles carry
# the weight, mass (summary.json, 22.8 mg) times gravity, within 1 %
# (measured 0.18 %: vertical equilibrium). The tilt (0.9 degrees at
# 10 mm) is free here, where the held rotations make it zero.
coshell_iol_test(iol.compression_iso11979.on_floor check_compression.py
                 compression_iso11979.prm --set ${no_vtu}
                 --set "Loads/Gravity=0, 0, -1635"
                 --set "Contact/Obstacle 3/Name=floor"
                 --set "Contact/Obstacle 3/Mesh file=../../meshes/contact/plane.geo"
                 --set "Contact/Obstacle 3/Translation=-5$<SEMICOLON> -5$<SEMICOLON> -0.42"
                 --set "Boundary conditions/Point conditions="
                 --gravity 1635)

# The paper's Fig. 3 (the lens mesh; 473 triangles there, 480 here,
# asserted within 2 %) and the compression sequence, regenerated from a
# run with doc/scripts/render_vtu.py (headless matplotlib 3-D) into
# build/tests/output/iol.figures/png/.
coshell_iol_test(iol.figures check_iol_figures.py compression_iso11979.prm
                 --figures ${CMAKE_CURRENT_BINARY_DIR}/output/iol.figures/png)

# Interactive coupling: a scripted session (targets 0.1, a comment, a bad
# line, 0.3, a target in the past, quit, and a line after quit) against
# the compression scene: one 'step' line per step (time, the force on
# each of the 2 clamps, the centroid, the real-time factor), 'done' per
# target, an error line for the bad one, nothing else on stdout, and the
# run ends at 0.3 s; each force as contact_forces.csv gives it and each
# centroid as the mean of the vertices of the VTU of that step (steps 4,
# 8 and 12), to the printed digits. The session again with Output/Steps between history
# rows = 5 (what a haptic loop would set): time_history.csv holds the
# full run's rows of steps 5 and 10 and of the last step, 12, where 'quit'
# ends the run, each the same to the digit; summary.json's quantities
# are the same (an invariance: both runs take the same steps).
coshell_iol_test(iol.interactive_protocol check_interactive.py
                 compression_iso11979.prm --obstacles 2 --history-rows 5)

# The coarse lens of the injection's ctests (203 triangles).
set(coarse_lens "Mesh/Gmsh parameters=optic_mesh_size = 0.9, haptic_mesh_size = 0.35")
# The injection's fold alone: every later stage off (a new stage of
# injection.prm goes here, not into each test).
set(fold_stage_only --set "Stage 2/Analysis type=none"
                    --set "Stage 3/Analysis type=none"
                    --set "Stage 4/Analysis type=none")
# The same scripted session on the injection scene (coarse lens, the
# first 0.3 s of the fold): 'step' lines with the forces on its 6
# obstacles (cartridge, plunger, bag, the two wings, the rod) as
# contact_forces.csv gives them and the centroids of its VTU (steps 10,
# 20 and 24 when written), the 'done' and error lines, the end at 0.3 s.
coshell_iol_test(iol.interactive_injection check_interactive.py
                 injection.prm --obstacles 6 --set ${coarse_lens})
# A session into the push (the plunger starts at rod_out_time = 1.3 s and
# meets the trailing haptic about 0.1 s later): the step lines' forces are
# contact_forces.csv's, and at t = 1.5 s the plunger's (the second force)
# is positive, the force a device on the plunger would render.
coshell_iol_test(iol.interactive_injection.push check_interactive.py
                 injection.prm --obstacles 6 --set ${coarse_lens}
                 --set ${no_vtu} --case "1.3 1.5 quit" "1.3 1.5" 1.5
                 --pushing 2)

# The plunger driven by a device (fold to 1.3 s, 1 mm of input by 1.5 s,
# then one step of 0.1 ms): the slope line's dF/ds against the central
# difference of three sessions whose last input differs by +-1e-6 mm.
# With the consistent tangent the slope is exact (measured 1.1e-5, the
# six printed digits); the scene's symmetric tangent leaves 4.3e-4, which
# doc/validation.md reports. Labelled long: it runs three folds.
coshell_iol_test(iol.interactive_plunger_slope check_input_slope.py
                 injection.prm --obstacles 6 --driven 2
                 --set "Contact/Obstacle 2/Translation=plunger_start$<SEMICOLON> 0$<SEMICOLON> axis_height"
                 --set "Contact/Obstacle 2/Input direction=1, 0, 0"
                 --set "Nonlinear solver/Tangent=consistent"
                 --lines "1.3$<SEMICOLON> 1.5 1" --last 1.5001 1.0001
                 --delta 1e-6 --rtol 2e-5)
set_tests_properties(iol.interactive_plunger_slope PROPERTIES LABELS "iol;long")

# The haptic modes' integrator, the seed paper's linearized implicit Euler
# (one linear solve per step), is consistent: on the first 0.2 s of push
# (coarse lens, the barrier, the linearized modes' 0.01 mm floor on
# friction's smoothing for every run) its plunger force over 0.5 mm of
# travel, reported at each step's end by the force's slopes, tends to
# that of the converged backward Euler at the same step (the floor makes
# the converged force depend on the step: 0.535, 0.473 and 0.427 mN at 1,
# 0.5 and 0.25 ms), its error at least halving with each halving of the
# step. Its error is far from small at the steps a haptic loop affords
# (doc/validation.md; the default lens's numbers are in doc/performance.md,
# "The linearized step's force at its end"). The mode that doc recommends
# instead, Newton stopped once a correction is at most 1 um, must stay
# within 1 % of the reference at 1 ms.
coshell_iol_test(iol.push.linearized_consistency
                 check_linearized_consistency.py injection.prm
                 --set ${coarse_lens}
                 --set "Contact/Stiction displacement=0.01"
                 --loose-tolerance 1e-3 --loose-within 0.01)

# Co-rotational kinematics tend to the linear ones as the load vanishes:
# the haptic at 1e-4 mN (load factor 0.01 of the prm's 0.01 mN), level 1,
# against the linear solution of the same mesh scaled to that load
# (tip_ux = -0.004641232, tip_uy = 0.003039388 mm). A consistency check of
# our two kinematics, not an independent reference: the difference falls
# at first order in the load (0.94 % at 1e-3 mN, 0.094 % here).
# Regression guard (label regression): the reference values are this
# code's own linear solution, written down from an earlier run.
coshell_scene_test(iol.haptic_compression.corotational_small_load_limit
  iol/haptic_compression.prm LABELS iol regression
  ARGS --set ${no_vtu} --set "Mesh/Refinement levels=1"
       --set "Element/Formulation=corotational"
       --set "Analysis/Type=nonlinear static"
       --set "Loads/Load factor=0.01" --set "Nonlinear solver/Load steps=1"
       --value tip_ux -0.004641232 3e-3 --value tip_uy 0.003039388 3e-3)

# The paper's Fig. 4 by tools (prm/iol/tuck.prm, default lens, 480
# triangles). Stage 1 tucks the haptics onto the optic: every gap >= 0
# (lens against the table, the holding rod, the mandrels, the anvils, the
# paddles, the plates and itself), each haptic's farthest point ends over
# the optic (3 mm off its axis allowed) and above its upper surface, and
# the optic is held (0.3 mm and 5 degrees about its axis allowed). Stage 2
# bends the optic by 30 degrees a side around the tucked haptics, each
# side's tools (plate, paddle, mandrel, anvil) turning as one rigid body:
# each rim point ends within 0.15 mm of where its side's tools carry it,
# and, that motion undone, each haptic's farthest point still lies over
# the optic and on top of it. The tools' work equals the lens's strain and
# kinetic energy, the drag's and friction's dissipation and the barrier's
# energy within 0.1 %, and the VTU series holds each stage's last step.
# Draws the tucked and the bent lens and the sequence
# into build/tests/output/iol.tuck/png/. The measured values are in
# doc/validation.md.
coshell_iol_test(iol.tuck check_tuck.py tuck.prm
                 --figures ${CMAKE_CURRENT_BINARY_DIR}/output/iol.tuck/png)

# Bad input of the injection scene: each gives a clear message, exits
# non-zero and leaves no summary.json. Moved 8 mm back, the cartridge's
# 4 mm tube would cross the flat lens (6 mm optic, 1.5 mm below the
# tube's axis): the lens starts inside its wall; a nozzle narrower than
# twice the lens's haptic thickness is refused by injector.geo, which gets
# the constants haptic_thickness that Material/Thickness uses and
# nozzle_radius (here 0.9 mm haptics against a 1.7 mm nozzle, which would
# pass 0.45 mm ones; both changed by Constants/Changes as a user would on
# the command line); a plunger wider than the nozzle's bore is refused
# (Constants/Positive: plunger_clearance, nozzle_radius - plunger_radius);
# a plunger speed of 0 or below is refused (Constants/Positive) where it is
# defined, before push_time divides by it; a stage whose duration names
# no constant is refused naming the stage; two obstacles writing one Force
# file are refused naming both.
set(injection ${COSHELL_PRM}/iol/injection.prm)
coshell_bad_input_test(iol_lens_inside_cartridge_wall
  "the shell starts inside obstacle 'cartridge' .Contact/Obstacle 1."
  ${injection} --set "Contact/Obstacle 1/Translation=-8$<SEMICOLON> 0$<SEMICOLON> axis_height")
coshell_bad_input_test(iol_nozzle_narrower_than_two_haptics
  "Contact/Obstacle 1 .'cartridge'.: gmsh could not mesh .*injector.geo': Error.*nozzle's inner diameter 2 . nozzle_radius = 1.7 mm is not wider than twice the haptic thickness .haptic_thickness = 0.9 mm"
  ${injection} --set "Constants/Changes=haptic_thickness = 0.9, nozzle_radius = 0.85, thinnest_fraction = 0.5")
# The tip (injection.prm's Constants/Requirements): narrower than 1.4 mm
# (the narrowest real tips), or narrower than the lens can pass by volume:
# a bore (2.0 mm: 3.1 mm^2) smaller than the optic's section (3.8 mm^2)
# for a shell that keeps its thickness, or (1.4 mm: 1.5 mm^2) smaller than
# that section thinned to half for one whose thickness can change.
coshell_bad_input_test(iol_tip_narrower_than_real_tips
  "Constants/Requirements: the cartridge's tip .2 nozzle_radius across. must be at least 1.4 mm .*is false with nozzle_radius = 0.6"
  ${injection} --set "Constants/Changes=nozzle_radius = 0.6")
coshell_bad_input_test(iol_tip_narrower_than_lens_by_volume
  "Constants/Requirements: the tip is narrower than the lens can pass by volume.*is false with nozzle_radius = 1, thinnest_fraction = 1, optic_section = 3.8"
  ${injection} --set "Constants/Changes=nozzle_radius = 1")
coshell_bad_input_test(iol_tip_narrower_than_thinned_lens_by_volume
  "Constants/Requirements: the tip is narrower than the lens can pass by volume.*is false with nozzle_radius = 0.7, thinnest_fraction = 0.5, optic_section = 3.8"
  ${injection} --set "Constants/Changes=nozzle_radius = 0.7, thinnest_fraction = 0.5")
coshell_bad_input_test(iol_plunger_wider_than_nozzle
  "Constants/Values: plunger_clearance = -0.05 must be > 0"
  ${injection} --set "Constants/Changes=plunger_radius = 1.8")
coshell_bad_input_test(iol_two_obstacles_one_force_file
  "Contact/Obstacle 6/Force file: 'plunger_force.csv' is Contact/Obstacle 2's Force file too"
  ${injection} --set "Contact/Obstacle 6/Force file=plunger_force.csv"
  --set "Contact/Obstacle 6/Force direction=0, 0, 1")
coshell_bad_input_test(iol_stage_duration_unknown_constant
  "Stage 2/Duration: cannot evaluate 'push_tim - rod_out_time'"
  ${injection} --set "Stage 2/Duration=push_tim - rod_out_time")
# A junction fillet too large for the lens: lens.geo refuses it, naming
# the fillet and the edge it does not fit (the C-loop's inner edge, and
# the modified-L's leg, which a 2 mm fillet would run past into the knee).
coshell_bad_input_test(iol_junction_fillet_too_large
  "gmsh could not mesh .*lens.geo': Error.*no junction fillet of radius 2 fits the C-loop's edge .radius 3.6. at the optic rim"
  ${injection} --set "Mesh/Gmsh parameters=junction_fillet = 2")
coshell_bad_input_test(iol_junction_fillet_past_the_knee
  "gmsh could not mesh .*lens.geo': Error.*a junction fillet of radius 2 reaches past the modified-L leg into its knee"
  ${injection} --set "Mesh/Gmsh parameters=junction_fillet = 2, haptic_type = 1")
# Refinement at the junctions: a negative size, a size no finer than the
# optic's (the grading would run backwards), and the single haptic of the
# compression test, which has no junction to refine.
coshell_bad_input_test(iol_junction_mesh_size_negative
  "gmsh could not mesh .*lens.geo': Error.*junction_mesh_size = -0.1 mm must be >= 0"
  ${injection} --set "Mesh/Gmsh parameters=junction_mesh_size = -0.1")
coshell_bad_input_test(iol_junction_mesh_size_not_finer
  "gmsh could not mesh .*lens.geo': Error.*junction_mesh_size = 0.6 mm must be below optic_mesh_size = 0.55 mm"
  ${injection} --set "Mesh/Gmsh parameters=junction_mesh_size = 0.6")
coshell_bad_input_test(iol_junction_mesh_size_without_junctions
  "gmsh could not mesh .*lens.geo': Error.*junction_mesh_size refines the haptic-optic junctions, which haptics_only = 1 leaves out"
  ${COSHELL_PRM}/iol/haptic_compression.prm
  --set "Mesh/Gmsh parameters=haptics_only = 1, junction_mesh_size = 0.05")
coshell_bad_input_test(iol_plunger_standing_still
  "Constants/Changes: plunger_speed = 0 must be > 0"
  ${injection} --set "Constants/Changes=plunger_speed = 0")
coshell_bad_input_test(iol_plunger_backwards
  "Constants/Changes: plunger_speed = -2 must be > 0"
  ${injection} --set "Constants/Changes=plunger_speed = -2")
# A change on the command line to a constant the scene does not have (a
# typo) is refused, not added unused.
coshell_bad_input_test(iol_unknown_constant_changed
  "Constants/Changes: 'plunger_sped' is not a constant of Constants/Values"
  ${injection} --set "Constants/Changes=plunger_sped = 1.5")

# The injection (prm/iol/injection.prm) on the coarse lens (203
# triangles: optic_mesh_size 0.9, haptic_mesh_size 0.35 mm), with the
# scene's friction (mu = 0.1 against the cartridge, the plunger, the wings,
# the rod and the lens itself; stiction velocity 0.1 mm/s).
# The fold stage alone, in the default suite: every gap >= 0 (lens against
# the wings, the holding rod and itself), the closing wings roll the optic
# from 6 mm across the injection axis to at most 3.7 mm (the closed wings'
# 4 mm bore less the rim's 0.3 mm thickness; measured 3.50 mm, 3.54 mm
# frictionless), and the work of the wings and the rod equals the lens's
# strain and kinetic energy, the drag's and friction's dissipation and the
# barrier's energy within 2 %.
# Draws the folded lens (the paper's Fig. 4) into
# build/tests/output/iol.injection.fold/png/.
set(frictionless
    --set "Contact/Obstacle 1/Friction coefficient=0"
    --set "Contact/Obstacle 2/Friction coefficient=0"
    --set "Contact/Obstacle 4/Friction coefficient=0"
    --set "Contact/Obstacle 5/Friction coefficient=0"
    --set "Contact/Obstacle 6/Friction coefficient=0"
    --set "Contact/Self contact friction coefficient=0")
coshell_iol_test(iol.injection.fold check_injection.py injection.prm
                 --set ${coarse_lens}
                 ${fold_stage_only}
                 --fold-only 3.7
                 --figures ${CMAKE_CURRENT_BINARY_DIR}/output/iol.injection.fold/png)
# The fold under time-step refinement: the same checks at Time
# integration/Maximum time step 5, 1 and 0.5 ms (iol.injection.fold is
# the scene's 20 ms), then the folded lenses compared. Friction's
# smoothing is the scene's eps = v_s dt (a law in the slip's velocity,
# which does not depend on the step; a fixed Stiction displacement would
# make friction fade as dt falls). Measured on the coarse lens (AMD EPYC,
# 2 cores): 264, 1378 and 2681 steps with 3, 41 and 41 failed ones;
# coshell's wall time 20, 43 and 127 s beside one other run and a build
# (39, 105 and 127 s under ctest -j2 beside a build). The 0.5 ms run and
# the comparison are labelled long.
function(coshell_fold_dt_test name dt)
  coshell_iol_test(${name} check_injection.py injection.prm
                   --set ${coarse_lens}
                   ${fold_stage_only}
                   --set "Time integration/Maximum time step=${dt}"
                   --fold-only 3.7)
  set_tests_properties(${name} PROPERTIES FIXTURES_SETUP fold_dt_runs)
endfunction()
coshell_fold_dt_test(iol.injection.fold.dt_5ms 0.005)
coshell_fold_dt_test(iol.injection.fold.dt_1ms 0.001)
coshell_fold_dt_test(iol.injection.fold.dt_0.5ms 0.0005)
set_tests_properties(iol.injection.fold.dt_0.5ms PROPERTIES LABELS "iol;long")
set_tests_properties(iol.injection.fold PROPERTIES FIXTURES_SETUP fold_dt_runs)
# The folded lens converges as dt falls, a self-convergence check (the
# reference is the 0.5 ms run, not an independent solution; label
# self_convergence): the largest distance of a lens vertex from its
# place in the 0.5 ms run falls by at least 2 from 20 to 5 ms and from 5
# to 1 ms (measured 0.0207, 0.0044 and 0.00037 mm: by 4.7 and 11.8, first
# order in dt; the optic's width across the axis 3.4990, 3.4990 and
# 3.4992 mm against 3.4992 mm). Each run's largest step is checked to be
# its Maximum time step. With a fixed Contact/Stiction displacement of
# 0.002 mm instead (the smoothing of a 20 ms step) the distances are
# 0.436, 0.415 and 0.129 mm, falling by 1.05 from 20 to 5 ms: this check
# fails.
set(fold_dt_output ${CMAKE_CURRENT_BINARY_DIR}/output)
add_test(NAME iol.injection.fold.dt_convergence
         COMMAND ${COSHELL_PYTHON}
                 ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_fold_convergence.py
                 --run 0.02 ${fold_dt_output}/iol.injection.fold
                 --run 0.005 ${fold_dt_output}/iol.injection.fold.dt_5ms
                 --run 0.001 ${fold_dt_output}/iol.injection.fold.dt_1ms
                 --run 0.0005 ${fold_dt_output}/iol.injection.fold.dt_0.5ms
                 --min-reduction 2
                 --table ${fold_dt_output}/iol.injection.fold.dt_convergence.csv)
set_tests_properties(iol.injection.fold.dt_convergence PROPERTIES
  LABELS "iol;long;self_convergence" FIXTURES_REQUIRED fold_dt_runs)
# The same fold without friction: the same checks.
coshell_iol_test(iol.injection.fold.frictionless check_injection.py
                 injection.prm
                 --set ${coarse_lens}
                 ${fold_stage_only}
                 ${frictionless}
                 --fold-only 3.7)
# The fold of the modified-L lens (lens.geo haptic_type = 1, coarse):
# the same checks (measured: optic 3.55 mm across, smallest gap 1.2e-4
# mm, energy remainder -0.008 % of the work).
set(coarse_modified_l "${coarse_lens}, haptic_type = 1")
coshell_iol_test(iol.injection.fold.modified_l check_injection.py
                 injection.prm
                 --set ${coarse_modified_l}
                 ${fold_stage_only}
                 --fold-only 3.7)
# The fold of a lens whose haptic-optic junctions are rounded (lens.geo
# junction_fillet = 0.25 mm, coarse: 428 triangles). The rest mesh's
# outline against fillets computed from the lens's dimensions alone
# (tests/scripts/lens_junctions.py): each fillet carries outline vertices,
# both tangent points among them; the rim and the haptic edge stop at the
# tangent points, short of the sharp lens's corner; every outline vertex
# near the optic lies on the rim, an edge or a fillet. The sharp lens fails
# the first two (eight failures, checked by hand). Then the fold's checks.
coshell_iol_test(iol.injection.fold.junction_fillet check_injection.py
                 injection.prm
                 --set "${coarse_lens}, junction_fillet = 0.25"
                 ${fold_stage_only}
                 --junction-fillet 0.25 --fold-only 3.7)
# The same for the modified-L lens, whose fillets meet the straight leg
# (measured by hand: gaps 1.2e-4 mm, optic 3.52 mm across, energy
# remainder 0.012 % of the work). The sharp modified-L fails the outline's
# first two kinds of check too (eight failures, by hand).
coshell_iol_test(iol.injection.fold.modified_l.junction_fillet
                 check_injection.py injection.prm
                 --set "${coarse_modified_l}, junction_fillet = 0.25"
                 ${fold_stage_only}
                 --junction-fillet 0.25 --haptic-type 1 --fold-only 3.7)
# The filleted coarse lens refined at its junctions (lens.geo
# junction_mesh_size = 0.175 mm, half the coarse haptic's size, within
# junction_mesh_radius = 0.15 mm of each fillet: 636 triangles against
# 428): the triangles there have that size (median of their longest
# edges at most 1.2 times it, 95th percentile at most 1.5 times; the
# unrefined lens fails both at every junction, 1.25 to 1.43 and 1.57 to
# 1.91 times, its fillets' own points refining it some), the outline
# still follows the fillets, and the fold's checks pass.
coshell_iol_test(iol.injection.fold.junction_refined check_injection.py
                 injection.prm
                 --set "${coarse_lens}, junction_fillet = 0.25, junction_mesh_size = 0.175, junction_mesh_radius = 0.15"
                 ${fold_stage_only}
                 --junction-fillet 0.25 --junction-refined 0.175 0.15
                 --fold-only 3.7)
# Co-rotational against linear kinematics on the same fold, to t = 0.6 s
# (wings 54 degrees closed): the optic's line rim-centre-rim stays within
# 3 % of its 6 mm with co-rotation (folding by bending; measured 1.9 %)
# and has grown by at least 30 % with linear kinematics (measured 76 %:
# each rotation taken as a stretch). The linear run goes on failing: it
# stalls at t = 0.964 s (step below 1e-6 s; doc/validation.md). Frictionless, as the kinematics alone are compared:
# with the scene's friction the wings hold the linear lens's rim, and its
# line grows by 11 % only (co-rotational 1.86 %). Draws both into
# build/tests/output/iol.fold.corotational_vs_linear/fold_kinematics.png.
coshell_iol_test(iol.fold.corotational_vs_linear check_fold_kinematics.py
                 injection.prm --set ${coarse_lens} ${frictionless} --until 0.6
                 --figure ${CMAKE_CURRENT_BINARY_DIR}/output/iol.fold.corotational_vs_linear/fold_kinematics.png)
# The whole injection on the coarse lens, in the default suite: fold,
# push, exit, deployment and settling (stage 4, 90 s for the lens to come
# to rest), with the scene's friction. Every check of check_injection.py:
# the fold's gaps, the folded optic in the nozzle, the lens out past the
# tip, the optic's shape at rest in the bag, the optic at rest (over the
# last 2 s; at the end of stage 3 it is still turning by 2 degrees/s), a
# finite positive plunger force, and the energy balance with friction's
# dissipation within 2 %. Draws the deployment sequence, each panel named
# by its stage. The measured values are in doc/validation.md.
coshell_iol_test(iol.injection check_injection.py injection.prm
                 --set ${coarse_lens}
                 --figures ${CMAKE_CURRENT_BINARY_DIR}/output/iol.injection/png)
# The whole injection of the modified-L lens (coarse): every check of
# iol.injection but the optic's shape at rest, which is reported and not
# asserted. The design sits at 2 %: held at 10 mm its arms bend the optic
# by about 2 % wherever they are held (1.72 % between the ISO clamps,
# 2.27 % in the bag at the end of the deploy stage, 1.91 % once settled;
# doc/validation.md, "The modified-L lens in the cartridge", which gives
# the measured values).
coshell_iol_test(iol.injection.modified_l check_injection.py injection.prm
                 --set ${coarse_modified_l}
                 --shape-not-asserted "the modified-L design bends its optic by about 2 % wherever it is held at 10 mm (1.72 % between the ISO clamps, 1.91 % at rest in the bag): a margin too thin to assert")
# A harder case: the whole injection of the coarse lens through a 3.3 mm
# nozzle instead of 3.5 (Constants/Changes, which the cartridge, the
# plunger and the bag's opening follow), every check of iol.injection,
# the optic's fold within the narrower bore. The plunger (3.2 mm)
# still leaves less room beside it in the 4 mm chamber (0.4 mm) than the
# haptic's thickness (0.45 mm), so the trailing haptic stays ahead of it;
# at 3.0 mm it slides beside the plunger and is pinched where the taper
# begins (doc/validation.md, "How narrow a nozzle the lens passes", which
# gives the measured values). Labelled long: iol.injection.sleeve_plunger
# below runs a narrower bore in the default suite.
coshell_iol_test(iol.injection.narrow_nozzle check_injection.py injection.prm
                 --set ${coarse_lens}
                 --set "Constants/Changes=nozzle_radius = 1.65")
set_tests_properties(iol.injection.narrow_nozzle PROPERTIES LABELS "iol;long")
# Narrower still, with the plunger's sleeve (injection.prm's Contact/
# Obstacle 7, switched on by its mesh): the whole injection of the coarse
# lens through a 2.8 mm nozzle, every check of iol.injection, the fold
# within the 2.8 mm bore. The sleeve fills the 4 mm chamber and stops in
# the taper (sleeve_stop, 9.75 mm here) while the 2.7 mm plunger goes on;
# without it the trailing haptic jams beside the plunger from 3.1 mm down
# (doc/validation.md, "How narrow a nozzle the lens passes", which gives
# the measured values). Also checks the sleeve's sleeve_force.csv.
# The sleeves are switched on by their meshes (injection.prm).
set(sleeve_on --set "Contact/Obstacle 7/Mesh file=../../meshes/contact/plunger.geo")
set(inner_sleeve_on --set "Contact/Obstacle 8/Mesh file=../../meshes/contact/plunger.geo")
coshell_iol_test(iol.injection.sleeve_plunger check_injection.py injection.prm
                 --set ${coarse_lens}
                 --set "Constants/Changes=nozzle_radius = 1.4"
                 ${sleeve_on})
# The default lens (480 triangles) through 2.4 mm with both sleeves
# (injection.prm's Contact/Obstacles 7 and 8): every check of
# iol.injection. The bore's area is 1.2 times the optic's section; at
# 2.2 mm the optic stalls at the nozzle's entrance. The measured values
# are in doc/validation.md. Labelled long.
coshell_iol_test(iol.injection.two_sleeves check_injection.py injection.prm
                 --set "Constants/Changes=nozzle_radius = 1.2"
                 ${sleeve_on} ${inner_sleeve_on})
set_tests_properties(iol.injection.two_sleeves PROPERTIES LABELS "iol;long")
# The whole injection at the slow end of real injectors, 1.5 mm/s (the
# scene's 5 mm/s is the fast end): Constants/Values derives push_time and
# the push stage's duration from plunger_speed, so the plunger makes the
# same 21.9 mm stroke in 14.6 s. Every check of check_injection.py (the
# measured values are in doc/validation.md). Labelled long.
coshell_iol_test(iol.injection.slow_plunger check_injection.py injection.prm
                 --set ${coarse_lens}
                 --set "Constants/Changes=plunger_speed = 1.5")
set_tests_properties(iol.injection.slow_plunger PROPERTIES LABELS "iol;long")
# The same without friction: every check of check_injection.py. Where the
# lens leaves the nozzle, cells of different thickness meet; the step
# filter and the barrier must agree there (doc/validation.md, "Why the
# lens stalled at the nozzle's exit"). The 1.7 mm plunger keeps the
# trailing haptic from slipping beside it (a 1.5 mm one lets it, and the
# taper pinches it; doc/validation.md). The measured values are in
# doc/validation.md. Labelled long.
coshell_iol_test(iol.injection.frictionless check_injection.py injection.prm
                 --set ${coarse_lens} ${frictionless})
set_tests_properties(iol.injection.frictionless PROPERTIES LABELS "iol;long")
