// Square plate [0,10]x[0,10] in the z = 0 plane, unstructured triangles.
// Physical curves: 0 at x = 0, 1 at x = 10, 2 at y = 0, 3 at y = 10 (the
// same ids as the generated rectangles). A vertex is kept at the centre.
L  = 10;
DefineConstant[ refinement_level = {0, Name "refinement_level"} ];
// Each refinement level halves the element size.
lc = 1.25 / 2^refinement_level;
Point(1) = {0, 0, 0, lc};
Point(2) = {L, 0, 0, lc};
Point(3) = {L, L, 0, lc};
Point(4) = {0, L, 0, lc};
Point(5) = {L/2, L/2, 0, lc};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Point{5} In Surface{1};
Physical Curve(2) = {1};
Physical Curve(1) = {2};
Physical Curve(3) = {3};
Physical Curve(0) = {4};
Physical Surface(0) = {1};
Mesh.Algorithm = 6;
