# Linear shell obstacle course (MacNeal & Harder 1985). Curved shells are
# approximated by flat facets, so each DKT case checks (1) the finest level
# against the published reference within a tolerance justified by the
# convergence table in doc/validation.md, and (2) the order observed from
# the three finest levels alone (no reference needed, so a reference that
# differs from the discretization's limit cannot fake a rate).
#
# The paper's bending element fails the constant-curvature patch test and
# converges to a wrong limit (doc/validation.md, "Linear shell obstacle
# course": +10.3 % roof, +12.3 % cylinder, +2.2-2.3 % hemisphere at level
# 5). That failure is asserted, with a margin below the measured error, so
# that a change of the element shows up here.
set(levels5 "Mesh/Refinement levels=0,1,2,3,4,5")

function(obstacle_course_case name qoi reference tolerance min_order przemieniecki_min_error)
  foreach(membrane ${COSHELL_TESTED_MEMBRANES})
    set(scene obstacle_course/${name}.prm)
    set(common --set ${levels5} --set ${no_vtu} --set "Element/Membrane element=${membrane}")
    coshell_scene_test(obstacle.${name}.${membrane}_dkt ${scene}
      ARGS ${common} --value ${qoi} ${reference} ${tolerance} --min-self-order ${min_order})
    coshell_scene_test(obstacle.${name}.${membrane}_przemieniecki ${scene}
      ARGS ${common} --set "Element/Bending element=przemieniecki"
           --error-above ${qoi} ${reference} ${przemieniecki_min_error})
  endforeach()
endfunction()

# Scordelis-Lo roof: reference 0.3024 (shallow-shell value; deep shell
# theory gives 0.3086). CST+DKT and ANDES+DKT flat facets both converge to
# about 0.3005 (0.6 % below) at O(h^2).
obstacle_course_case(scordelis_lo_roof free_edge_deflection -0.3024 0.01 1.5 0.05)
# Pinched cylinder: reference 1.8248e-5 under the load.
obstacle_course_case(pinched_cylinder load_point_deflection -0.000018248 0.005 1.5 0.05)
# Pinched hemisphere: reference 0.094 (MacNeal & Harder; thin-shell
# solutions quoted since are 0.0924-0.0940). Slow, O(h^1.3), approach.
obstacle_course_case(pinched_hemisphere load_point_displacement 0.094 0.01 1.0 0.01)

# ANDES on the coarse hemisphere. Without the curvature scaling of its
# drilling terms (doc/theory.md, section 14) ANDES+DKT locks: 91 %, 48 %,
# 6.4 % too stiff at 4 x 4, 8 x 8 and 16 x 16 squares per quarter. With the defaults (K_h: c = 30, alpha_b:
# c_b = 0.1) it is 1.8 %, 0.40 %, 0.59 %; the 8 x 8 mesh must be within
# 5 % and the 16 x 16 within 1.5 %, and c = c_b = 0 (the optimal element
# unscaled) must still show the locking, so that the scaling, not a change
# elsewhere, is what the first two measure.
foreach(level_tolerance "1;0.05" "2;0.015")
  list(GET level_tolerance 0 level)
  list(GET level_tolerance 1 tolerance)
  coshell_scene_test(obstacle.pinched_hemisphere.andes_dkt_level_${level}
    obstacle_course/pinched_hemisphere.prm
    ARGS --set "Mesh/Refinement levels=${level}" --set ${no_vtu}
         --set "Element/Membrane element=andes"
         --value load_point_displacement 0.094 ${tolerance})
endforeach()
coshell_scene_test(obstacle.pinched_hemisphere.andes_dkt_unscaled_locks
  obstacle_course/pinched_hemisphere.prm
  ARGS --set "Mesh/Refinement levels=1" --set ${no_vtu}
       --set "Element/Membrane element=andes"
       --set "Element/ANDES curvature scaling=0"
       --set "Element/ANDES basic drilling scaling=0"
       --error-above load_point_displacement 0.094 0.4)
# ANDES+DKT no coarser than CST+DKT at any level 0-5, on the hemisphere
# (the issue's criterion; measured 1.8 / 0.40 / 0.59 / 0.56 / 0.53 / 0.51 %
# against 7.7 / 0.91 / 1.4 / 1.2 / 0.74 / 0.58 %) and on the roof (0.39 /
# 0.10 / 0.60 / 0.63 / 0.62 / 0.62 % against 33 / 14 / 4.7 / 1.7 / 0.89 /
# 0.69 %). Not on the pinched cylinder: there ANDES is better at levels
# 0-3 (48 % against 51 % at level 0) and worse at 4-5 (0.11 % against
# 0.06 %, 0.17 % against 0.15 %), doc/validation.md.
foreach(case_qoi_reference "pinched_hemisphere;load_point_displacement;0.094"
                           "scordelis_lo_roof;free_edge_deflection;-0.3024")
  list(GET case_qoi_reference 0 case)
  list(GET case_qoi_reference 1 qoi)
  list(GET case_qoi_reference 2 reference)
  coshell_scene_test(obstacle.${case}.andes_dkt_no_coarser_than_cst_dkt
    obstacle_course/${case}.prm
    ARGS --set ${levels5} --set ${no_vtu} --set "Element/Membrane element=andes"
         --no-coarser-than "Element/Membrane element=cst" ${qoi} ${reference})
endforeach()
