# Linear plate benchmarks against analytic Kirchhoff plate solutions
# (Timoshenko & Woinowsky-Krieger, Theory of Plates and Shells, 1959).
set(levels "Mesh/Refinement levels=0,1,2,3,4")

# Clamped square plate, uniform pressure: w = 0.126532 q (D = 100, L = 10).
# DKT must converge at O(h^2) and reach 0.1 % at the finest level.
foreach(pattern crossed same-diagonal alternating)
  coshell_scene_test(clamped_square_pressure.dkt.${pattern}
    plates/clamped_square_pressure.prm
    ARGS --set ${levels} --set "Mesh/Triangle pattern=${pattern}"
         --value center_deflection 0.126532 1e-3
         --min-rate 1.8 --max-rate 2.2)
endforeach()
