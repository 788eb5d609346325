# Contact with rigid meshed obstacles: equilibrium with the reaction,
# the gap over every iterate, friction, wrapping and a funnel, and bad
# input. The measured values are appended to output/contact_report.csv.
set(CHECK_CONTACT ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_contact.py)
set(CONTACT_REPORT ${CMAKE_CURRENT_BINARY_DIR}/output/contact_report.csv)

# coshell_contact_test(NAME PRM ARGS check_contact arguments...)
function(coshell_contact_test name prm)
  cmake_parse_arguments(T "" "" "ARGS" ${ARGN})
  add_test(NAME ${name}
           COMMAND ${COSHELL_PYTHON} ${CHECK_CONTACT}
                   --coshell $<TARGET_FILE:coshell>
                   --prm ${COSHELL_PRM}/${prm}
                   --output ${CMAKE_CURRENT_BINARY_DIR}/output/${name}
                   --report ${CONTACT_REPORT} ${T_ARGS})
  set_tests_properties(${name} PROPERTIES LABELS contact)
endfunction()

# A plate resting on a plane under gravity: the plane carries the weight
# rho h A g = 1.2e-9 * 0.5 * 100 * 9810 = 5.886e-4 N, within 1e-6, and
# its moment about the origin is that of the weight at the plate's centre
# (5, 5): mx = -5 W, my = 5 W. The barrier keeps the gap positive at every
# iterate; the penalty lets in a penetration (reported).
coshell_contact_test(contact.plate_on_plane.barrier contact/plate_on_plane.prm
  ARGS --reaction fz -0.0005886 1e-6 --reaction mx -0.002943 1e-6
  --reaction my 0.002943 1e-6 --gap-nonnegative --gap-below 0.05
  --active-pairs 81)
# The barrier's stiffness from the scene's load (Barrier stiffness scale =
# load): kappa = q / |b'(d/2)| = 5.886e-6 / (0.05 (ln 2 + 1/2)) =
# 9.8663e-5 N/mm^3, with q = rho h g the weight per area, so that the
# vertex-triangle pairs carry q at half the activation distance, 0.025 mm
# (edge-edge pairs carry a little of it: measured 0.0267 at the last
# step, asserted within 10 %). The default (material) scale floats the
# plate at 0.0494 of 0.05, where the barrier's stiffness vanishes.
coshell_contact_test(contact.plate_on_plane.barrier_load_scale
  contact/plate_on_plane.prm
  ARGS --set "Contact/Barrier stiffness scale=load"
  --reaction fz -0.0005886 1e-6 --gap-nonnegative
  --summary barrier_stiffness 9.866e-5 9.867e-5 --last-gap 0.025 0.1)
# Hard case, a vertex exactly on an obstacle edge: an STL plane of 5 x 5
# squares split along y = x + 6k, so the diagonal y = x runs under the
# plate's vertices (0.625 k, 0.625 k). With every pair in reach (the
# default) the reaction is the weight within 1e-6. (With Pairs = local
# minima Newton does not converge on this plane: see doc/validation.md.)
set(diagonal_plane "Contact/Obstacle 1/Mesh file=${CMAKE_CURRENT_SOURCE_DIR}/data/plane_diagonals.stl")
coshell_contact_test(contact.plate_on_plane.vertex_on_edge contact/plate_on_plane.prm
  ARGS --set ${diagonal_plane} --set "Contact/Pairs=all"
  --reaction fz -0.0005886 1e-6 --gap-nonnegative)

# Dropped from the same place (dynamics, backward Euler, dt = 1 ms, 40
# steps): at rest on the plane, the same reaction. The penalty's
# penetration x balances the weight per area p = rho h g = 5.886e-6 MPa in
# the penalty's cubic start (x < eps = h/100): k x^2 / (2 eps) = p, so
# x = sqrt(2 eps p / k) = 1.7157e-4 mm with k = E/h = 2 N/mm^3.
# That closed form counts the plane's pressure on vertex-triangle pairs
# alone; edge-edge pairs (on by default) add to it where the plate's
# edges cross the plane's (-1.757e-4 mm, 2.4 % deeper; the reaction is
# the weight either way), so the test keeps them off.
coshell_contact_test(contact.plate_on_plane.barrier_dynamic contact/plate_on_plane.prm
  ARGS --set "Analysis/Type=dynamic"
  --reaction fz -0.0005886 1e-6 --gap-nonnegative --gap-below 0.05)
coshell_contact_test(contact.plate_on_plane.penalty_dynamic contact/plate_on_plane.prm
  ARGS --set "Analysis/Type=dynamic" --set "Contact/Method=penalty"
  --set "Contact/Edge-edge pairs=false"
  --reaction fz -0.0005886 1e-6 --last-gap -0.00017157 1e-3)

# The penalty's step filter. The plane rises at 600 mm/s under the plate,
# 0.6 mm per 1 ms step: more than the plate's 0.5 mm thickness, so in the
# first step it jumps past the plate's mid-surface, and a penalty, which
# only acts on penetration, never sees it: without the filter the plate
# falls freely as if the plane were not there (backward Euler:
# uz = -g dt^2 n (n + 1) / 2 = -0.14715 mm after n = 5 steps). With
# Penalty step filter = 0.9 every move of the plane and every correction
# stops short of 0.9 of the offset (h/2 = 0.25 mm): the plate rides on the
# plane, its mid-surface between 0.225 and 0.25 mm above the plane's
# 2.73 mm (asserted 2.98 mm within 1 %), and the largest penetration stays
# below (1 - 0.9) h/2 = 0.025 mm.
set(rising_plane
    --set "Analysis/Type=dynamic" --set "Contact/Method=penalty"
    --set "Contact/Obstacle 1/Translation=0$<SEMICOLON> 0$<SEMICOLON> -0.27 + 600 * t"
    --set "Time integration/End time=0.005" --set "Output/Write VTU=false"
    --set "Quantities of interest/Point values=centre_uz: 5 5 0 uz")
coshell_contact_test(contact.plate_on_plane.penalty_step_filter
  contact/plate_on_plane.prm
  ARGS ${rising_plane} --set "Contact/Penalty step filter=0.9"
  --final centre_uz 2.98 0.01 --summary largest_penetration 0 0.025)
coshell_contact_test(contact.plate_on_plane.penalty_tunnels_without_filter
  contact/plate_on_plane.prm
  ARGS ${rising_plane} --final centre_uz -0.14715 1e-6)

# Friction on an incline (gravity tilted by theta, mu = 0.2, dynamics):
# at theta = 20 deg (tan theta > mu) the plate slides with
# a = g (sin theta - mu cos theta) = 1511.54 mm/s^2, fitted over
# t in [0.01, 0.04] s once it has landed, within 2 %; without friction
# with g sin theta = 3355.22 mm/s^2. At theta = 10 deg (tan theta < mu) it
# sticks: after landing it creeps less than 1e-4 mm in 25 ms (sliding
# freely it would go 2.8 mm).
set(incline contact/incline_friction.prm)
coshell_contact_test(contact.incline_friction.sliding ${incline}
  ARGS --slope centre_ux 0.01 0.04 1511.54 0.02 --gap-nonnegative)
coshell_contact_test(contact.incline_friction.frictionless ${incline}
  ARGS --set "Contact/Obstacle 1/Friction coefficient=0"
  --slope centre_ux 0.01 0.04 3355.217 0.02 --gap-nonnegative)
coshell_contact_test(contact.incline_friction.sticking ${incline}
  ARGS --set "Loads/Gravity=1703.489, 0, -9660.965"
  --change centre_ux 0.015 0.04 1e-4 --gap-nonnegative)
# A tool that grips and lets go: Friction coefficient = if(t < 0.025,
# 0.5, 0.2) at theta = 20 deg sticks (tan theta < 0.5; creeps less than
# 1e-4 mm from 0.012 to 0.025 s, measured 6.4e-6) and then slides at
# g (sin theta - 0.2 cos theta) = 1511.54 mm/s^2 within 2 % (measured
# 1508.5, fitted over [0.028, 0.04] s).
coshell_contact_test(contact.incline_friction.grip_then_release ${incline}
  ARGS --set "Contact/Obstacle 1/Friction coefficient=if(t < 0.025, 0.5, 0.2)"
  --change centre_ux 0.012 0.025 1e-4
  --slope centre_ux 0.028 0.04 1511.54 0.02 --gap-nonnegative)
# A floor on friction's smoothing length (Stiction displacement, here
# 1000 and 100 times IPC's v dt = 1e-6 mm): sliding keeps Coulomb's law
# (the slip per step, about 0.05 mm, is far above the floor); sticking
# becomes a creep of less than the floor per step, asserted as less than
# 25 floors over the 25 steps (the price of the floor).
coshell_contact_test(contact.incline_friction.sliding_stiction_floor ${incline}
  ARGS --set "Contact/Stiction displacement=1e-3"
  --slope centre_ux 0.01 0.04 1511.54 0.02 --gap-nonnegative)
coshell_contact_test(contact.incline_friction.sticking_stiction_floor ${incline}
  ARGS --set "Contact/Stiction displacement=1e-4"
  --set "Loads/Gravity=1703.489, 0, -9660.965"
  --change centre_ux 0.015 0.04 2.5e-3 --gap-nonnegative)
# The same two with edge-edge pairs, which carry the obstacle's friction
# too: a flat plate on a flat plane feels both kinds of pair (IPC counts
# both); frictionless edge pairs would let part of the normal force escape
# friction (sliding 32 % fast, and no sticking; doc/validation.md).
coshell_contact_test(contact.incline_friction.sliding_edge_edge ${incline}
  ARGS --set "Contact/Edge-edge pairs=true"
  --slope centre_ux 0.01 0.04 1511.54 0.02 --gap-nonnegative)
coshell_contact_test(contact.incline_friction.sticking_edge_edge ${incline}
  ARGS --set "Contact/Edge-edge pairs=true"
  --set "Loads/Gravity=1703.489, 0, -9660.965"
  --change centre_ux 0.015 0.04 1e-4 --gap-nonnegative)

# Funnel: a plunger pushes a 4 mm strip through a cone into a 3 mm tube
# (dynamics, 0.85 s). The barrier keeps every iterate of every step apart
# (smallest gap >= 0) and the plunger pushes (force on it along -x between
# 1 mN and 1 N: a sanity bound, not a reference). The penalty only
# reports its largest penetration: here it is 0.1 mm, the half thickness,
# which means the strip's mid-surface crossed an obstacle's surface (the
# penalty has no step filter; a stiffer penalty, 500 N/mm^3, does no
# better). That is the failure the barrier exists to prevent; the test
# asserts only that the penetration is reported. Hard case: the barrier
# with 5x larger steps (0.5 mm of plunger travel per step, more than
# twice the activation distance plus the strip's half thickness): still
# no interpenetration.
set(funnel contact/funnel.prm)
# Energy (frictionless): the plunger's work on the strip, from its force
# and its prescribed displacement, equals the strip's strain and kinetic
# energy, the drag's dissipation and the barrier's energy within 2 %
# (measured: 0.11 %; penalty 0.03 %). The plunger's Force file along
# (-2, 0, 1), normalized by coshell, has the plunger's rows of
# contact_forces.csv projected on that unit vector (a consistency check
# of two outputs).
coshell_contact_test(contact.funnel.barrier ${funnel}
  ARGS --set "Output/Write VTU=false" --gap-nonnegative
  --force-range 2 fx -1 -0.001 --summary smallest_gap 0 1
  --energy-balance 0.02
  --set "Contact/Obstacle 2/Force file=plunger_tilted.csv"
  --set "Contact/Obstacle 2/Force direction=-2, 0, 1"
  --force-file plunger_tilted.csv 2 -2 0 1 plunger_displacement)
# With friction (mu = 0.1 on funnel and plunger; it converges with the
# edge-edge pairs) and the energy line search: the same guarantee, the
# plunger pushes, and the energy balance closes with friction's
# dissipation counted (the funnel, fixed, does no work). The line
# search's trial evaluations put the obstacles back: a trial that kept
# the plunger advanced against an undone shell shape would open gaps of
# -6e-3 mm.
coshell_contact_test(contact.funnel.barrier_friction ${funnel}
  ARGS --set "Output/Write VTU=false"
  --set "Contact/Obstacle 1/Friction coefficient=0.1"
  --set "Contact/Obstacle 2/Friction coefficient=0.1"
  --set "Nonlinear solver/Line search=true"
  --gap-nonnegative --force-range 2 fx -1 -0.001 --energy-balance 0.02)
coshell_contact_test(contact.funnel.penalty ${funnel}
  ARGS --set "Output/Write VTU=false" --set "Contact/Method=penalty"
  --force-range 2 fx -1 -0.001 --summary largest_penetration 1e-9 0.1
  --energy-balance 0.02)
# The penalty with friction (mu = 0.1 on funnel and plunger, the energy
# line search): the strip gets through, the penetration is reported as
# above, and the balance closes with friction's dissipation (measured:
# remainder 1e-4 of the work). Stiction velocity 0.1 mm/s, 1 % of the
# plunger's speed: with the default 1e-3 mm/s Newton stalls at t = 0.041
# s (the step fell below 1e-5 s), since each step cut shrinks friction's
# smoothing length v_s dt, as in the IOL fold (doc/validation.md).
coshell_contact_test(contact.funnel.penalty_friction ${funnel}
  ARGS --set "Output/Write VTU=false" --set "Contact/Method=penalty"
  --set "Contact/Obstacle 1/Friction coefficient=0.1"
  --set "Contact/Obstacle 2/Friction coefficient=0.1"
  --set "Contact/Stiction velocity=0.1"
  --set "Nonlinear solver/Line search=true"
  --force-range 2 fx -1 -0.001 --summary largest_penetration 1e-9 0.1
  --energy-balance 0.02)
coshell_contact_test(contact.funnel.large_steps ${funnel}
  ARGS --set "Output/Write VTU=false" --set "Time integration/Time step=0.05"
  --set "Time integration/Maximum time step=0.05" --gap-nonnegative
  --summary smallest_gap 0 1)

# Strip wrapped on a cylinder (statics): an end moment curls a clamped
# strip (EI = 1, h = 0.2) round a rigid cylinder (R = 2). The elastica
# keeps it clear below M* = EI / (R + h/2) and puts it on the cylinder at
# M* (bracketed by load steps 0.5 % apart, asserted within 1 %; without
# the thickness offset M* would be 5 % higher); there the centre line
# lies on the radius R + h/2 within 1 %. At 1.1 M* the tip bears on the
# cylinder with the force of an inextensible clamped arc held at its tip
# (Castigliano, 4 (M - M*) / (pi r)) within 2 %.
add_test(NAME contact.strip_on_cylinder
         COMMAND ${COSHELL_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_wrap.py
                 --coshell $<TARGET_FILE:coshell>
                 --prm ${COSHELL_PRM}/contact/strip_on_cylinder.prm
                 --output ${CMAKE_CURRENT_BINARY_DIR}/output/contact.strip_on_cylinder
                 --radius 2 --thickness 0.2 --start-gap 0.002 --length 3.3
                 --bending-stiffness 1 --moment-max 0.523809524)
set_tests_properties(contact.strip_on_cylinder PROPERTIES LABELS contact)

# Hard cases on a very thin strip (h / L = 1e-3) lying on a plane under a
# pressure q = 1e-3 (resultant 0.01 N). Squeezed: a rod presses its
# middle until the room between rod and plane is h + 0.6 d (rod force
# 10.6 N, a thousand times the pressure's). Grazing: the rod comes down to
# a room of h + 1.5 d, inside both barrier layers, and slides 8 mm along
# the strip. Both converge with no iterate interpenetrating, and the
# massless strip passes everything to the plane: the obstacles' forces
# add up to the pressure's resultant within 1e-6. (Squeezed to h + 0.6 d
# and then slid, Newton stalls at a relative residual of 1e-7 and the
# step size collapses, with a clear error: see doc/validation.md.)
# The squeeze converges with vertex-triangle pairs alone. With edge-edge
# pairs (the default) Newton stalls at load factor 0.996
# (relative residual 1.0 at a strip vertex under the rod) and the run
# stops with a clear error; ..._edge_edge_stalls asserts that error, so
# that a fix shows.
set(thin_strip contact/thin_strip_squeeze.prm)
coshell_contact_test(contact.hard.thin_strip_squeezed ${thin_strip}
  ARGS --set ${no_vtu} --set "Contact/Edge-edge pairs=false"
  --reaction fz -0.01 1e-6 --gap-nonnegative --force-range 2 fz 1 100)
coshell_bad_input_test(contact_thin_strip_squeezed_edge_edge_stalls "the step size .* fell below its minimum 1e-09: Newton did not converge"
  ${COSHELL_PRM}/${thin_strip} --set ${no_vtu})
# The rod pushed on until the room it leaves (0.99 h) is thinner than the
# strip (a jam): the failure names the two obstacles that pinch the strip
# and the vertex.
coshell_bad_input_test(contact_shell_pinched "the shell is pinched between obstacles 'plane' and 'rod' at vertex"
  ${COSHELL_PRM}/${thin_strip} --set ${no_vtu}
  --set "Contact/Obstacle 2/Translation=5$<SEMICOLON> 0$<SEMICOLON> 0.52 - 0.0156 * t"
  --set "Nonlinear solver/Maximum step cuts=3")
coshell_contact_test(contact.hard.grazing ${thin_strip}
  ARGS --set ${no_vtu} --set "Nonlinear solver/Load steps=50"
  --set "Contact/Obstacle 2/Translation=1 + 8*max(0, (t - 0.2)/0.8)$<SEMICOLON> 0$<SEMICOLON> 0.52 - 0.014*min(1, t/0.2)"
  --reaction fz -0.01 1e-6 --gap-nonnegative --gap-below 0.001)

# Hard case for the guarantee: a rigid knife whose straight edge crosses a
# coarse plate between its vertices (knife vertices beyond the plate),
# pushed 0.38 down. With edge-edge pairs the edge stays at least h/2 =
# 0.05 above the deformed mid-surface along its whole length (measured
# 0.059, vertically) and carries the plate's push. Without them nothing
# sees the edge: it passes through the plate with no force at all
# (clearance -0.3), the hole the edge-edge pairs close; that run is
# asserted too, so the clearance check is known to bite.
set(knife contact/knife_on_plate.prm)
coshell_contact_test(contact.hard.knife_edge_edge ${knife}
  ARGS --gap-nonnegative --edge-clearance 0.05 1 --force-range 1 fz 1 10000)
coshell_contact_test(contact.hard.knife_without_edge_pairs ${knife}
  ARGS --set "Contact/Edge-edge pairs=false" --edge-clearance -1 0
  --force-range 1 fz 0 0)
# Friction on edge-edge pairs: the knife (mu = 0.3) pressed 0.38 down in
# the first half of the path, then slid 1 mm along its edge at that
# depth, 0.1 mm per load step (2000 times the stiction length, 1e-3 x
# 0.05). Its edge touches the plate through edge-edge pairs only, so
# Coulomb's law, ft = mu fn at the last step, tests their friction:
# -0.3029 measured, within 2 % (the lagged normal forces of pairs that
# entered that step, and a 5 N lateral force of the frictionless pairs
# at the plate's border, 0.4 %, both count).
coshell_contact_test(contact.hard.knife_edge_edge_friction ${knife}
  ARGS --set "Contact/Obstacle 1/Friction coefficient=0.3"
  --set "Contact/Obstacle 1/Translation=3.1$<SEMICOLON> max(0, 2 * t - 1)$<SEMICOLON> 0.08 - 0.38 * min(2 * t, 1)"
  --gap-nonnegative --force-ratio 1 fy fz -0.3 0.02)

# Bad input names the obstacle and what is wrong with it.
set(plane_scene ${COSHELL_PRM}/contact/plate_on_plane.prm)
set(incline_scene ${COSHELL_PRM}/contact/incline_friction.prm)
coshell_bad_input_test(contact_missing_obstacle_mesh
  "Contact/Obstacle 1 .'plane'.: mesh file .*no_such_obstacle.stl' does not exist"
  ${plane_scene} --set "Contact/Obstacle 1/Mesh file=no_such_obstacle.stl")
coshell_bad_input_test(contact_empty_obstacle_mesh
  "Contact/Obstacle 1 .'plane'.: mesh file .*empty_obstacle.stl' has no triangles"
  ${plane_scene} --set "Contact/Obstacle 1/Mesh file=${data}/empty_obstacle.stl")
coshell_bad_input_test(contact_shell_starts_inside
  "the shell starts inside obstacle 'plane' .Contact/Obstacle 1.: shell vertex"
  ${plane_scene} --set "Contact/Obstacle 1/Translation=0$<SEMICOLON> 0$<SEMICOLON> -0.2")
coshell_bad_input_test(contact_zero_input_direction
  "Contact/Obstacle 1/Input direction: must not be zero"
  ${plane_scene} --set "Contact/Obstacle 1/Input direction=0, 0, 0")
# An obstacle's Force file needs a nonzero direction (and a direction
# needs a file), is a plain NAME.csv beside the run's own CSV files (not a
# path, not one of them) and is one obstacle's.
coshell_bad_input_test(contact_force_file_without_direction
  "Contact/Obstacle 1/Force direction: required with a Force file"
  ${plane_scene} --set "Contact/Obstacle 1/Force file=plane_force.csv")
coshell_bad_input_test(contact_force_direction_without_file
  "Contact/Obstacle 1/Force direction: given without a Force file"
  ${plane_scene} --set "Contact/Obstacle 1/Force direction=0, 0, 1")
coshell_bad_input_test(contact_force_direction_zero
  "Contact/Obstacle 1/Force direction: must not be zero"
  ${plane_scene} --set "Contact/Obstacle 1/Force file=plane_force.csv"
  --set "Contact/Obstacle 1/Force direction=0, 0, 0")
coshell_bad_input_test(contact_force_file_is_a_path
  "Contact/Obstacle 1/Force file: 'forces/plane.csv' is not a plain file name NAME.csv"
  ${plane_scene} --set "Contact/Obstacle 1/Force file=forces/plane.csv"
  --set "Contact/Obstacle 1/Force direction=0, 0, 1")
coshell_bad_input_test(contact_force_file_is_the_runs_own
  "Contact/Obstacle 1/Force file: 'contact_forces.csv' is a file the run writes itself"
  ${plane_scene} --set "Contact/Obstacle 1/Force file=contact_forces.csv"
  --set "Contact/Obstacle 1/Force direction=0, 0, 1")
coshell_bad_input_test(contact_input_with_checkpoints
  "Output/Checkpoint interval: a checkpoint would not hold the input"
  ${plane_scene} --interactive --set "Analysis/Type=dynamic"
  --set "Contact/Obstacle 1/Input direction=0, 0, 1"
  --set "Output/Checkpoint interval=0.01")
# A failed solve with friction names its smoothing length: the plate's
# dynamic start (a 4.48 N barrier push) with friction 0.3 and sticking
# smoothed over v_s dt alone (1e-6 mm at 1 ms, less with every step cut)
# fails at its first step; with a 1e-3 mm floor it runs.
coshell_bad_input_test(contact_friction_too_stiff_to_solve
  "friction on [0-9]+ pairs smooths sticking over [0-9.e-]+ .length units: Contact/Stiction velocity times the step, at least Contact/Stiction displacement."
  ${plane_scene} --set "Analysis/Type=dynamic"
  --set "Contact/Obstacle 1/Friction coefficient=0.3")
coshell_bad_input_test(contact_negative_friction
  "Contact/Obstacle 1 .'plane'.: Friction coefficient: -0.1 is negative"
  ${plane_scene} --set "Contact/Obstacle 1/Friction coefficient=-0.1")
coshell_bad_input_test(contact_friction_negative_later
  "obstacle .incline.: Friction coefficient is -0.02 at t = 0.026 s"
  ${incline_scene} --set "Contact/Obstacle 1/Friction coefficient=0.5 - 20 * t")
coshell_bad_input_test(contact_load_scaled_barrier_without_load
  "Barrier stiffness scale = load needs a dead load"
  ${plane_scene} --set "Loads/Gravity=0, 0, 0"
  --set "Contact/Barrier stiffness scale=load")
coshell_bad_input_test(contact_negative_self_friction
  "Contact/Self contact friction coefficient: -0.2 is negative"
  ${COSHELL_PRM}/contact/self_friction_incline.prm
  --set "Contact/Self contact friction coefficient=-0.2")
coshell_bad_input_test(contact_negative_stiction_displacement
  "Contact/Stiction displacement=-1.*does not match"
  ${plane_scene} --set "Contact/Stiction displacement=-1")
coshell_bad_input_test(contact_penalty_step_filter_of_one
  "Contact/Penalty step filter: 1 must be below 1"
  ${plane_scene} --set "Contact/Penalty step filter=1")
# A penalty too soft for the step filter: at 1e-6 N/mm^3 the rising plane
# can press the plate no harder than 1e-6 x 0.025 N/mm^2 within the
# filter's (1 - 0.9) h/2, far below the plate's weight (5.9e-6 N/mm^2), so
# the plane cannot reach its position. Newton fails the step; so does the
# linearized scheme when an obstacle's move is blocked (rather than accept
# frozen steps and write results as if the plane had risen). Both name
# the obstacle and the two parameters that cure it.
set(soft_penalty ${plane_scene} ${rising_plane}
    --set "Contact/Penalty step filter=0.9"
    --set "Contact/Penalty stiffness=1e-6")
set(penalty_cure "raise Contact/Penalty stiffness .1e-06 N/mm.3 in mm-N units. or lower Contact/Penalty step filter")
coshell_bad_input_test(contact_penalty_jam_newton
  "Newton did not converge.*obstacle 'plane'.*${penalty_cure}"
  ${soft_penalty})
coshell_bad_input_test(contact_penalty_jam_linearized
  "the linearized step failed: a prescribed move is still pending.*obstacle 'plane'.*${penalty_cure}"
  ${soft_penalty} --set "Time integration/Method=linearized implicit euler")
coshell_bad_input_test(contact_unparsable_motion
  "Contact/Obstacle 1/Translation: cannot parse '0.*-0.3..'"
  ${plane_scene} --set "Contact/Obstacle 1/Translation=0$<SEMICOLON> 0$<SEMICOLON> -0.3**")
coshell_bad_input_test(contact_with_arc_length
  "Contact works with load control, not with the arc-length method"
  ${plane_scene} --set "Nonlinear solver/Method=arc length")

# Self contact: a thin plate (h = 0.01, a thousandth of the bending
# stiffness) lying on a clamped plate (h = 0.1, D = 100), both pieces of
# one non-matching mesh, statics. All of its weight q = 1e-3 reaches the
# lower plate through vertex-triangle pairs of the shell with itself, as
# a uniform pressure: centre deflection 0.00126532 q L^4 / D =
# -1.26532e-4 (Timoshenko), measured +0.49 % (1472 triangles) and
# +0.030 % (5688), asserted within 1e-3 at the finer mesh. The gap stays
# positive at every iterate; every upper vertex carries its share.
coshell_scene_test(contact.self.plate_on_plate contact/plate_on_plate.prm
  LABELS contact
  ARGS --set ${no_vtu} --set "Mesh/Refinement levels=0,1"
       --value center_deflection -0.000126532 1e-3)
coshell_contact_test(contact.self.plate_on_plate.gap contact/plate_on_plate.prm
  ARGS --set ${no_vtu} --gap-nonnegative --gap-below 0.001)
# Friction of the shell against itself (Self contact friction
# coefficient): the incline's three cases with a clamped lower plate of
# the same shell as the plane (mu = 0.2): sliding at g (sin theta - mu
# cos theta) = 1511.54 mm/s^2 (measured 8.5e-6 off), frictionless at
# g sin theta (1.6e-6 off), sticking at 10 degrees (1.6e-5 mm of creep).
set(self_incline contact/self_friction_incline.prm)
coshell_contact_test(contact.self.friction_incline.sliding ${self_incline}
  ARGS --slope centre_ux 0.01 0.04 1511.54 0.02 --gap-nonnegative)
coshell_contact_test(contact.self.friction_incline.frictionless ${self_incline}
  ARGS --set "Contact/Self contact friction coefficient=0"
  --slope centre_ux 0.01 0.04 3355.217 0.02 --gap-nonnegative)
coshell_contact_test(contact.self.friction_incline.sticking ${self_incline}
  ARGS --set "Loads/Gravity=1703.489, 0, -9660.965"
  --change centre_ux 0.015 0.04 1e-4 --gap-nonnegative)
# Self contact roll-up: an end moment winds a strip (EI = 1, h = 0.05,
# rolling length 6) past a full turn onto its own clamped tail. Stage 1
# (statics, M = 0.975 x the full-turn moment): the tip rests on the tail;
# the tail's force on it and its position match an elastica with a
# vertical tip force (shooting in the checker) within 2 % and 0.2 % of
# the length (measured 0.51 %, 0.012 %). Stage 2 (damped dynamics through
# the snap where the tip slides past the clamp line, to 1.25 x): at rest
# the strip turns through more than a full turn, both layers carry
# contact force and it sums to zero; the gap stays positive at every
# iterate.
# coshell_rollup_test(NAME ARGS extra arguments...)
function(coshell_rollup_test name)
  add_test(NAME ${name}
           COMMAND ${COSHELL_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_rollup.py
                   --coshell $<TARGET_FILE:coshell>
                   --prm ${COSHELL_PRM}/contact/self_contact_rollup.prm
                   --output ${CMAKE_CURRENT_BINARY_DIR}/output/${name}
                   --root-x 1.5 --length 6 --thickness 0.05 --bending-stiffness 1
                   --moment-max 1.308996939 --force-tolerance 0.02
                   --position-tolerance 0.002 ${ARGN})
  set_tests_properties(${name} PROPERTIES LABELS contact)
endfunction()
coshell_rollup_test(contact.self.rollup)
# The same with shell edges against shell edges as well (25 active pairs
# at the end instead of 6; the same elastica values within 0.05 %).
coshell_rollup_test(contact.self.rollup.edge_edge
  --set "Contact/Edge-edge pairs=true")
coshell_bad_input_test(contact_shell_starts_in_self_contact "the shell starts in contact with itself .Contact/Self contact.: shell vertex"
  ${COSHELL_PRM}/contact/plate_on_plate.prm --set "Mesh/Gmsh parameters=upper_height = 0.05")

# Checkpoint and restart with contact (friction mu = 0.1): the barrier's
# stiffness, the plunger lagging behind its motion, the works of the energy
# bookkeeping and friction's lagged normal forces are in the checkpoint,
# so a run resumed from the middle one, or after SIGINT, ends in the
# uninterrupted run's state to 1e-12 (measured: bit for bit), with the same
# time_history.csv, contact_forces.csv and plunger Force file rows.
add_test(NAME restart.funnel_friction
  COMMAND ${COSHELL_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_restart.py
          --coshell $<TARGET_FILE:coshell> --prm ${COSHELL_PRM}/${funnel}
          --output ${CMAKE_CURRENT_BINARY_DIR}/output/restart.funnel_friction
          --set "Output/Write VTU=false"
          --set "Contact/Obstacle 1/Friction coefficient=0.1"
          --set "Contact/Obstacle 2/Force file=plunger_force.csv"
          --set "Contact/Obstacle 2/Force direction=1, 0, 0"
          --force-file plunger_force.csv
          --end 0.4 --interval 0.1 --tolerance 1e-12)
set_tests_properties(restart.funnel_friction PROPERTIES LABELS contact)

# An obstacle driven by the interactive protocol (a haptic device's
# plunger): the plane under the plate of plate_on_plane.prm, dynamic,
# meets the plate at 0.01 s, stops until 0.015 s and then pushes it up,
# 0.07 mm in all by 0.04 s. Once prescribed by its Translation (-0.27 +
# 2 min(t, 0.01) + 2 max(t - 0.015, 0)), once by the session's lines
# '0.01 0.02', '0.015' (the input held) and '0.04 0.07' with Input
# direction = 0, 0, 1 on a Translation of -0.27: the input path is linear
# between its samples and ramps from the present, as the prescribed
# motion does, so the two runs must agree to round-off (measured: to the
# digit): time_history.csv and contact_forces.csv within 1e-12 relative.
# Then the refusals, each an error line with the run going on: an input
# for a time before the present, a line that is neither 't' nor 't s',
# an input when no obstacle takes one.
add_test(NAME contact.interactive_input_drives_obstacle
  COMMAND ${COSHELL_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_interactive_input.py
          --coshell $<TARGET_FILE:coshell> --prm ${plane_scene}
          --output ${CMAKE_CURRENT_BINARY_DIR}/output/contact.interactive_input_drives_obstacle
          --obstacles 1 --set "Analysis/Type=dynamic"
          --prescribed "Contact/Obstacle 1/Translation=0$<SEMICOLON> 0$<SEMICOLON> -0.27 + 2 * min(t, 0.01) + 2 * max(t - 0.015, 0)"
          --driven "Contact/Obstacle 1/Translation=0$<SEMICOLON> 0$<SEMICOLON> -0.27"
          --driven "Contact/Obstacle 1/Input direction=0, 0, 1"
          --targets "0.01 0.015 0.04" --inputs "0.02 - 0.07")
set_tests_properties(contact.interactive_input_drives_obstacle PROPERTIES LABELS contact)
# The slope line's dF/ds (the Schur complement of the shell in the tangent
# extended by the input) against the central difference of three
# sessions that differ in the last input by +-1e-5 mm; backward Euler,
# the barrier resting the plate on the rising plane. The tolerance is
# twice the rounding of the six digits printed (measured 4.2e-6).
add_test(NAME contact.interactive_input_slope
  COMMAND ${COSHELL_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_input_slope.py
          --coshell $<TARGET_FILE:coshell> --prm ${plane_scene}
          --output ${CMAKE_CURRENT_BINARY_DIR}/output/contact.interactive_input_slope
          --obstacles 1 --set "Analysis/Type=dynamic"
          --set "Contact/Obstacle 1/Translation=0$<SEMICOLON> 0$<SEMICOLON> -0.27"
          --set "Contact/Obstacle 1/Input direction=0, 0, 1"
          --driven 1 --lines "0.01 0.02$<SEMICOLON> 0.015" --last 0.016 0.02
          --delta 1e-5 --rtol 2e-5)
set_tests_properties(contact.interactive_input_slope PROPERTIES LABELS contact)
# The same in the linearized implicit Euler, whose step reports the force
# at its end as the force of its one evaluation plus the force's slopes
# times the correction (Contact::extrapolate_loads()). The slope line is
# that reported force's derivative but for one term: the change of the
# pair Hessians themselves over the correction (a third derivative times
# the correction), which the step's linear system does not hold; on this
# step it is 1.8e-3 of the slope. The force is smooth there: its
# one-sided differences part by 2e-3 at delta 1e-6, 2e-2 at 1e-5 and 0.2
# at 1e-4, in proportion to delta. Asserted within 5e-3. (The force at
# the step's start would match no finite difference better than the
# slope's order of magnitude.)
add_test(NAME contact.interactive_input_slope.linearized
  COMMAND ${COSHELL_PYTHON} ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_input_slope.py
          --coshell $<TARGET_FILE:coshell> --prm ${plane_scene}
          --output ${CMAKE_CURRENT_BINARY_DIR}/output/contact.interactive_input_slope.linearized
          --obstacles 1 --set "Analysis/Type=dynamic"
          --set "Time integration/Method=linearized implicit euler"
          --set "Contact/Obstacle 1/Translation=0$<SEMICOLON> 0$<SEMICOLON> -0.27"
          --set "Contact/Obstacle 1/Input direction=0, 0, 1"
          --driven 1 --lines "0.01 0.02$<SEMICOLON> 0.015" --last 0.016 0.02
          --delta 1e-6 --rtol 5e-3)
set_tests_properties(contact.interactive_input_slope.linearized PROPERTIES LABELS contact)
