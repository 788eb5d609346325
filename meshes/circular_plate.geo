// Circular plate of radius a = 5 centred at the origin in the z = 0 plane,
// unstructured triangles. Physical curve 1 = the rim, physical surface 0 =
// the plate. coshell passes the refinement level as 'refinement_level'.
a  = 5;
DefineConstant[ refinement_level = {0, Name "refinement_level"} ];
// Each refinement level halves the element size.
lc = 1.0 / 2^refinement_level;
Point(1) = {0, 0, 0, lc};
Point(2) = {a, 0, 0, lc};
Point(3) = {0, a, 0, lc};
Point(4) = {-a, 0, 0, lc};
Point(5) = {0, -a, 0, lc};
Circle(1) = {2, 1, 3};
Circle(2) = {3, 1, 4};
Circle(3) = {4, 1, 5};
Circle(4) = {5, 1, 2};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
// Keep a vertex at the centre, where the deflection is measured.
Point{1} In Surface{1};
Physical Curve(1) = {1, 2, 3, 4};
Physical Surface(0) = {1};
Mesh.Algorithm = 6; // Frontal-Delaunay
