# Linear shell obstacle course (MacNeal & Harder 1985). Curved shells are
# approximated by flat facets, so each case checks (1) the finest level
# against the published reference within a tolerance justified by the
# convergence table in doc/validation.md, and (2) the order observed from
# the three finest levels alone (no reference needed, so a reference that
# differs from the discretization's limit cannot fake a rate).
set(levels5 "Mesh/Refinement levels=0,1,2,3,4,5")

foreach(membrane ${COSHELL_TESTED_MEMBRANES})
  # Scordelis-Lo roof: reference 0.3024 (shallow-shell value; deep shell
  # theory gives 0.3086). CST+DKT and ANDES+DKT flat facets both converge
  # to about 0.3005 (0.6 % below) at O(h^2).
  coshell_scene_test(obstacle.scordelis_lo_roof.${membrane}_dkt
    obstacle_course/scordelis_lo_roof.prm
    ARGS --set ${levels5} --set ${no_vtu}
         --set "Element/Membrane element=${membrane}"
         --value free_edge_deflection -0.3024 0.01 --min-self-order 1.5)
  # Pinched cylinder: reference 1.8248e-5 under the load.
  coshell_scene_test(obstacle.pinched_cylinder.${membrane}_dkt
    obstacle_course/pinched_cylinder.prm
    ARGS --set ${levels5} --set ${no_vtu}
         --set "Element/Membrane element=${membrane}"
         --value load_point_deflection -0.000018248 0.005 --min-self-order 1.5)
  # Pinched hemisphere: reference 0.094 (MacNeal & Harder; thin-shell
  # solutions quoted since are 0.0924-0.0940). Slow, O(h^1.3), approach.
  coshell_scene_test(obstacle.pinched_hemisphere.${membrane}_dkt
    obstacle_course/pinched_hemisphere.prm
    ARGS --set ${levels5} --set ${no_vtu}
         --set "Element/Membrane element=${membrane}"
         --value load_point_displacement 0.094 0.01 --min-self-order 1.0)
endforeach()

# The paper's bending element on the same shells: it fails the
# constant-curvature patch test, so it converges to a wrong limit
# (doc/validation.md, "Linear shell obstacle course": +10.3 % on the roof,
# +12.3 % on the cylinder, +2.2-2.3 % on the hemisphere at level 5). The
# failure is asserted, with margins below the measured errors, so that the
# day the element changes this test says so.
foreach(membrane ${COSHELL_TESTED_MEMBRANES})
  coshell_scene_test(obstacle.scordelis_lo_roof.${membrane}_przemieniecki
    obstacle_course/scordelis_lo_roof.prm
    ARGS --set ${levels5} --set ${no_vtu}
         --set "Element/Membrane element=${membrane}"
         --set "Element/Bending element=przemieniecki"
         --error-above free_edge_deflection -0.3024 0.05)
  coshell_scene_test(obstacle.pinched_cylinder.${membrane}_przemieniecki
    obstacle_course/pinched_cylinder.prm
    ARGS --set ${levels5} --set ${no_vtu}
         --set "Element/Membrane element=${membrane}"
         --set "Element/Bending element=przemieniecki"
         --error-above load_point_deflection -0.000018248 0.05)
  coshell_scene_test(obstacle.pinched_hemisphere.${membrane}_przemieniecki
    obstacle_course/pinched_hemisphere.prm
    ARGS --set ${levels5} --set ${no_vtu}
         --set "Element/Membrane element=${membrane}"
         --set "Element/Bending element=przemieniecki"
         --error-above load_point_displacement 0.094 0.01)
endforeach()
