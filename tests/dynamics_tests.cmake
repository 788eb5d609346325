# Dynamics: free vibration against Leissa's plate frequencies, conservation
# laws of a free-flying plate, the order of accuracy in dt, rigid spin,
# stability at large steps, a released displacement-driven stage, and bad
# input. The measured values are appended to output/dynamics_report.csv.
set(CHECK_DYNAMICS ${CMAKE_CURRENT_SOURCE_DIR}/scripts/check_dynamics.py)
set(TIME_ORDER ${CMAKE_CURRENT_SOURCE_DIR}/scripts/time_order.py)
set(DYNAMICS_REPORT ${CMAKE_CURRENT_BINARY_DIR}/output/dynamics_report.csv)
set(cantilever dynamics/cantilever_plate_free_vibration.prm)
set(free_flying dynamics/free_flying_plate.prm)

# coshell_dynamics_test(NAME PRM ARGS check_dynamics arguments...)
function(coshell_dynamics_test name prm)
  cmake_parse_arguments(T "" "" "ARGS" ${ARGN})
  add_test(NAME ${name}
           COMMAND ${COSHELL_PYTHON} ${CHECK_DYNAMICS}
                   --coshell $<TARGET_FILE:coshell>
                   --prm ${COSHELL_PRM}/${prm}
                   --output ${CMAKE_CURRENT_BINARY_DIR}/output/${name}
                   --report ${DYNAMICS_REPORT} ${T_ARGS})
  set_tests_properties(${name} PROPERTIES LABELS dynamics)
endfunction()

# Cantilever plate released from its static deflection (16x16 crossed,
# dt = T_1/50). Generalized alpha with rho_inf = 1: the period is Leissa's
# first (T_1 = 2 pi / 3.492) within 1 %, the amplitude of the last period
# is the first's within 0.5 % (the rest is the small share of the second
# bending mode), and the energy is conserved (linear problem).
coshell_dynamics_test(dynamics.cantilever_plate_free_vibration.generalized_alpha
  ${cantilever} ARGS --stage 2 --period tip_w 1.7993 0.01
  --amplitude-change tip_w 0.005 --drift total_energy 1e-6 initial)
# Backward Euler damps: per step by 1/sqrt(1 + (omega h)^2) (omega h =
# 2 pi/50), so the last period's amplitude is 0.0436 of the first's eight
# periods before; asserted below 0.1. The linearized scheme is the same
# on this linear problem.
foreach(method "implicit euler" "linearized implicit euler")
  string(REPLACE " " "_" tag "${method}")
  coshell_dynamics_test(dynamics.cantilever_plate_free_vibration.${tag}
    ${cantilever} ARGS --stage 2 --set "Time integration/Method=${method}"
    --period tip_w 1.7993 0.02 --amplitude-decay tip_w 0.9)
endforeach()

# Free-flying plate tumbling about a non-principal axis, 1000 steps of
# 0.02 s (20 s, about 3.5 turns): linear momentum conserved to 1e-8 of
# m |v| ~ 0.5, angular momentum drifts < 0.1 %, total energy < 1 % with
# rho_inf = 1. The Euler schemes: momentum asserted, angular momentum and
# energy drift reported (they dissipate).
coshell_dynamics_test(dynamics.free_flying_plate.generalized_alpha
  ${free_flying} ARGS --drift linear_momentum 1e-8 0.5
  --drift angular_momentum 1e-3 initial --drift total_energy 0.01 initial)
foreach(method "implicit euler" "linearized implicit euler")
  string(REPLACE " " "_" tag "${method}")
  coshell_dynamics_test(dynamics.free_flying_plate.${tag}
    ${free_flying} ARGS --set "Time integration/Method=${method}"
    --drift linear_momentum 1e-8 0.5 --drift angular_momentum 1 initial
    --no-growth total_energy 0)
endforeach()

# Order of accuracy in dt on the free-flying plate (final positions of two
# corners after 1 s against a run at dt = 0.0015625 s).
foreach(method_order "generalized alpha:1.8" "implicit euler:0.9")
  string(REPLACE ":" ";" pair "${method_order}")
  list(GET pair 0 method)
  list(GET pair 1 order)
  string(REPLACE " " "_" tag "${method}")
  add_test(NAME dynamics.time_order.${tag}
    COMMAND ${COSHELL_PYTHON} ${TIME_ORDER} --coshell $<TARGET_FILE:coshell>
            --prm ${COSHELL_PRM}/${free_flying}
            --output ${CMAKE_CURRENT_BINARY_DIR}/output/dynamics.time_order.${tag}
            --end 1 --dt 0.1 0.05 0.025 0.0125 --reference-dt 0.0015625
            --qoi corner_x corner_z far_x far_y far_z --min-order ${order}
            --set "Time integration/Method=${method}"
            --set "Nonlinear solver/Residual tolerance=1e-10")
  set_tests_properties(dynamics.time_order.${tag} PROPERTIES LABELS dynamics)
endforeach()

# Rigid spin about the normal, 1 rad/s, 1.5 degrees per step: the nodal
# rotation angle after 150 degrees equals omega t within 1e-3 rad. (At 30
# degrees per step it is 7 % short: the translations move on R^3, not on
# SE(3); see doc/validation.md.)
set(spin --set "Mass and damping/Initial angular velocity=0$<SEMICOLON> 0$<SEMICOLON> 1"
         --set "Mass and damping/Initial velocity=-1.0*(y-0.5)$<SEMICOLON> 1.0*(x-0.5)$<SEMICOLON> 0"
         --set "Quantities of interest/Point values=rz: 0 0 0 rz"
         --set "Time integration/End time=2.617993878")
coshell_dynamics_test(dynamics.rigid_spin ${free_flying} ARGS ${spin}
  --set "Time integration/Time step=0.02617993878"
  --set "Time integration/Maximum time step=0.02617993878"
  --final rz 2.617993878 1e-3)

# Stability: steps of 0.27 s, about 100 times the explicit limit
# h_e / c = 0.088 / 33 s (membrane wave speed sqrt(E / rho (1 - nu^2))):
# the implicit schemes stay bounded and the energy does not grow.
# Generalized alpha needs rho_inf = 0 here: with rho_inf = 0.5 the energy
# of this tumbling plate grows by 2.6 %, with 0.8 by 7.6 % (see
# doc/validation.md).
set(large_steps --set "Time integration/Time step=0.27"
                --set "Time integration/Maximum time step=0.27"
                --set "Time integration/End time=10.8")
foreach(method_radius "generalized alpha:0" "implicit euler:1" "linearized implicit euler:1")
  string(REPLACE ":" ";" pair "${method_radius}")
  list(GET pair 0 method)
  list(GET pair 1 radius)
  string(REPLACE " " "_" tag "${method}")
  coshell_dynamics_test(stability.free_flying_plate_100x_explicit_step.${tag}
    ${free_flying} ARGS ${large_steps} --set "Time integration/Method=${method}"
    --set "Time integration/Spectral radius=${radius}"
    --no-growth total_energy 0 --drift linear_momentum 1e-8 0.5)
endforeach()

# Displacement-driven stage then release: the strip rolled into a circle by
# a prescribed end rotation springs open in a damped dynamic stage and
# comes to rest flat.
coshell_dynamics_test(stages.strip_roll_up_then_release
  dynamics/strip_roll_up.prm ARGS --stage 2
  --final tip_u 0 1e-3 --final tip_w 0 1e-3)

# Bad input. ($<SEMICOLON> is ';' inside a test command.)
set(vibration ${COSHELL_PRM}/${cantilever})
coshell_bad_input_test(negative_density "Material: density = -1 must be non-negative"
  ${vibration} --set "Material/Density=-1")
coshell_bad_input_test(dynamics_without_mass "dynamics and modes need mass: Material/Density must be positive"
  ${vibration} --set "Material/Density=0")
coshell_bad_input_test(negative_time_step "Time integration/Time step = -0.1 must be positive"
  ${vibration} --set "Time integration/Time step=-0.1")
coshell_bad_input_test(minimum_above_maximum_step "Minimum time step = 0.1 exceeds Maximum time step = 0.01"
  ${vibration} --set "Time integration/Minimum time step=0.1"
  --set "Time integration/Maximum time step=0.01")
coshell_bad_input_test(unparsable_initial_velocity "Initial velocity: cannot parse"
  ${vibration} --set "Mass and damping/Initial velocity=1$<SEMICOLON> 2$<SEMICOLON> (")

# Cantilever plate natural frequencies against Leissa (1969), Table 4.41
# (nu = 0.3, lambda^2 = omega here): within 1.5 % at the finest level (32 x
# 32 crossed, 4096 triangles), with the consistent and the lumped mass.
foreach(mass consistent lumped)
  coshell_scene_test(modes.cantilever_plate.${mass}
    dynamics/cantilever_plate_modes.prm LABELS dynamics
    ARGS --set "Mass and damping/Mass matrix=${mass}" --set ${no_vtu}
         --value omega_1 3.492 0.015 --value omega_2 8.525 0.015
         --value omega_3 21.43 0.015 --value omega_4 27.33 0.015
         --value omega_5 31.11 0.015)
endforeach()
coshell_bad_input_test(modes_of_a_free_plate_without_shift "rigid-body motion.s. free"
  ${COSHELL_PRM}/dynamics/cantilever_plate_modes.prm
  --set "Boundary conditions/Conditions=")

# Energy bookkeeping on the flapping plate under gravity (co-rotational,
# rho_inf = 1): total energy - work of the loads + dissipated energy stays
# constant within 0.1 % of the work done, undamped and with Rayleigh mass
# damping plus normal and tangential drag.
coshell_dynamics_test(dynamics.flapping_plate.energy_balance
  dynamics/flapping_plate.prm
  ARGS --set "Time integration/Spectral radius=1" --energy-balance 1e-3)
coshell_dynamics_test(dynamics.flapping_plate.energy_balance_damped
  dynamics/flapping_plate.prm
  ARGS --set "Time integration/Spectral radius=1"
       --set "Mass and damping/Rayleigh mass coefficient=10"
       --set "Mass and damping/Normal drag=1e-8"
       --set "Mass and damping/Tangential drag=1e-9" --energy-balance 1e-3)
