# Every kind of bad input must give a clear message and a non-zero exit,
# and leave no summary.json behind.
set(plate ${COSHELL_PRM}/plates/clamped_square_pressure.prm)
set(data ${CMAKE_CURRENT_SOURCE_DIR}/data)

coshell_bad_input_test(missing_prm "cannot read parameter file .*no_such_file.prm"
  ${data}/no_such_file.prm)
coshell_bad_input_test(prm_is_directory "cannot read parameter file"
  ${data})
coshell_bad_input_test(unknown_parameter "unknown_parameter.prm.*Line <3>.*Stifness"
  ${data}/unknown_parameter.prm)
coshell_bad_input_test(ill_typed_value "ill_typed_value.prm.*Line <2>.*Poisson"
  ${data}/ill_typed_value.prm)
coshell_bad_input_test(unknown_set_parameter "--set 'Material/Stifness=1'.*Stifness"
  ${plate} --set "Material/Stifness=1")
coshell_bad_input_test(ill_typed_set_value "--set 'Mesh/Subdivisions x=four'"
  ${plate} --set "Mesh/Subdivisions x=four")
coshell_bad_input_test(missing_mesh "mesh file .*no_such_mesh.msh' does not exist"
  ${plate} --set "Mesh/Source=gmsh" --set "Mesh/Gmsh file=${data}/no_such_mesh.msh")
coshell_bad_input_test(unreadable_mesh "cannot read gmsh mesh .*not_a_mesh.msh"
  ${plate} --set "Mesh/Source=gmsh" --set "Mesh/Gmsh file=${data}/not_a_mesh.msh")
coshell_bad_input_test(degenerate_triangle "degenerate triangle: cell 1 with vertices"
  ${plate} --set "Mesh/Source=gmsh" --set "Mesh/Gmsh file=${data}/degenerate_triangle.msh")
coshell_bad_input_test(zero_thickness "Material: thickness h = 0 must be positive"
  ${plate} --set "Material/Thickness=0")
coshell_bad_input_test(negative_thickness "Material: thickness h = -0.1 must be positive"
  ${plate} --set "Material/Thickness=-0.1")
coshell_bad_input_test(unparsable_thickness "Material/Thickness: cannot parse 'thin' as 1 expression.s. of x, y, z, region"
  ${plate} --set "Material/Thickness=thin")
# The plate spans 0 <= x <= 10: the thickness turns negative past x = 5.
coshell_bad_input_test(thickness_expression_negative "Material: at triangle [0-9]+ .centroid [5-9][.0-9]* .*region 0.: thickness h = -[0-9.e-]+ must be positive"
  ${plate} --set "Material/Thickness=0.1 - x / 50")
coshell_bad_input_test(density_expression_negative "Material: at triangle [0-9]+ .*region 0.: density = -"
  ${plate} --set "Material/Density=if(x < 9, 1, -1)")
coshell_bad_input_test(malformed_gmsh_parameter "Mesh/Gmsh parameters: 'haptic width = 1' is not of the form 'name = value'"
  ${plate} --set "Mesh/Source=gmsh" --set "Mesh/Gmsh file=${CMAKE_SOURCE_DIR}/meshes/iol/lens.geo"
  --set "Mesh/Gmsh parameters=haptic width = 1")
coshell_bad_input_test(region_pose_without_axis "Quantities of interest/Region poses: '0 5 5 0 0 0 0' is not 'region cx cy cz ax ay az'"
  ${plate} --set "Quantities of interest/Region poses=plate: 0 5 5 0 0 0 0")
coshell_bad_input_test(region_pose_of_missing_region "Quantities of interest/Region poses: plate: the mesh has fewer than three vertices in region 7"
  ${plate} --set "Quantities of interest/Region poses=plate: 7 5 5 0 0 0 1")
coshell_bad_input_test(edge_force_unknown_boundary "Loads/Edge forces: boundary id 7, which the mesh does not have"
  ${plate} --set "Loads/Edge forces=7: 1 0 0")
coshell_bad_input_test(interactive_without_dynamics "--interactive drives dynamic stages, and this scene has none"
  ${plate} --interactive)
coshell_bad_input_test(zero_youngs_modulus "Material: Young's modulus E = 0 must be positive"
  ${plate} --set "Material/Young's modulus=0")
coshell_bad_input_test(poisson_ratio_too_large "Poisson's ratio = 0.5 is outside"
  ${plate} --set "Material/Poisson's ratio=0.5")
coshell_bad_input_test(poisson_ratio_too_small "Poisson's ratio = -1 is outside"
  ${plate} --set "Material/Poisson's ratio=-1")
coshell_bad_input_test(unknown_boundary_condition "unknown boundary condition 'glued'"
  ${plate} --set "Boundary conditions/Conditions=0: glued")
coshell_bad_input_test(boundary_id_not_in_mesh "boundary id 7, which the mesh does not have"
  ${plate} --set "Boundary conditions/Conditions=7: clamped")
coshell_bad_input_test(no_supports "6 rigid-body motion.s. free"
  ${plate} --set "Boundary conditions/Conditions=")
coshell_bad_input_test(bad_point_load "Loads: point load '1 2 : 0 0 1'.*three numbers"
  ${plate} --set "Loads/Point forces=1 2 : 0 0 1")
coshell_bad_input_test(both_parts_off "both off"
  ${plate} --set "Element/Membrane element=off" --set "Element/Bending element=off")
coshell_bad_input_test(unknown_command_line_option "unexpected argument '--frobnicate'"
  ${plate} --frobnicate)
coshell_bad_input_test(hinge_only "1 rigid-body motion.s. free.*translation z.*rotation y"
  ${plate} --set "Boundary conditions/Conditions=0: fixed ux uy uz")

# An in-plane load with the membrane switched off acts on DoFs no element
# stiffens: the linear solve refuses it, naming the DoF.
coshell_bad_input_test(load_on_unstiffened_dof
  "a load acts on DoF 12, which no element stiffens"
  ${plate} --set "Element/Membrane element=off"
  --set "Loads/Point forces=0.5 0.5 0 : 1 0 0" --set "Mesh/Refinement levels=1")

# Element/Thickness stretch needs the co-rotational CST shell; Face
# pressure needs the stretch; an incompressible law has no thick membrane.
set(squeeze ${COSHELL_PRM}/thickness/plate_squeeze_frictionless.prm)
coshell_bad_input_test(thickness_stretch_linear "Element: Thickness stretch needs Formulation = corotational"
  ${squeeze} --set "Element/Formulation=linear")
coshell_bad_input_test(thickness_stretch_andes "Element: Thickness stretch needs Membrane element = cst"
  ${squeeze} --set "Element/Membrane element=andes")
coshell_bad_input_test(face_pressure_without_stretch "Element: Face pressure needs Thickness stretch = true"
  ${squeeze} --set "Element/Thickness stretch=false")
coshell_bad_input_test(thickness_stretch_incompressible "Material: Poisson's ratio = 0.5 is outside"
  ${squeeze} --set "Material/Poisson's ratio=0.5")
