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

# The whole lens between two concave clamps closing from 13.1 to 10 mm
# (ISO 11979-3): the barrier's gap stays non-negative at every step, the
# two clamp forces balance within 1 % (quasi-static equilibrium), the
# force grows with the compression and ends finite and positive.
# The force curve is written to compression.csv (mN against mm).
coshell_iol_test(iol.compression_iso11979 check_compression.py
                 compression_iso11979.prm --set ${no_vtu})

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
# run ends at 0.3 s.
coshell_iol_test(iol.interactive_protocol check_interactive.py
                 compression_iso11979.prm --obstacles 2)

# Co-rotational kinematics tend to the linear ones as the load vanishes:
# the haptic at 1e-4 mN (load factor 0.01 of the prm's 0.01 mN), level 1,
# against the linear solution of the same mesh scaled to that load
# (tip_ux = -0.004641232, tip_uy = 0.003039388 mm). A consistency check of
# our two kinematics, not an independent reference: the difference falls
# at first order in the load (0.94 % at 1e-3 mN, 0.094 % here).
coshell_scene_test(iol.haptic_compression.corotational_small_load_limit
  iol/haptic_compression.prm LABELS iol
  ARGS --set ${no_vtu} --set "Mesh/Refinement levels=1"
       --set "Element/Formulation=corotational"
       --set "Analysis/Type=nonlinear static"
       --set "Loads/Load factor=0.01" --set "Nonlinear solver/Load steps=1"
       --value tip_ux -0.004641232 3e-3 --value tip_uy 0.003039388 3e-3)
