// Scordelis-Lo roof, one quarter (MacNeal & Harder 1985): cylinder of
// radius 25 with its axis along y, opening half-angle 40 degrees, half
// length 25. Physical curves: 1 = mid-length arc (y = 0, symmetry y),
// 2 = end arc on the rigid diaphragm (y = 25), 3 = crown line (x = 0,
// symmetry x), 4 = free straight edge. Structured triangles, n x n squares.
DefineConstant[ refinement_level = {0, Name "refinement_level"} ];
R = 25;
half_angle = 40 * Pi / 180;
half_length = 25;
n = 4 * 2^refinement_level;
Point(1) = {0, 0, 0};
Point(2) = {0, 0, R};
Point(3) = {R * Sin(half_angle), 0, R * Cos(half_angle)};
Circle(1) = {2, 1, 3};
Transfinite Curve{1} = n + 1;
out[] = Extrude {0, half_length, 0} { Curve{1}; Layers{n}; };
// out[0]: far arc, out[1]: surface, out[2]: line from point 3 (free edge),
// out[3]: line from point 2 (crown); gmsh lists the end point's line first.
Physical Curve(1) = {1};
Physical Curve(2) = {out[0]};
Physical Curve(3) = {out[3]};
Physical Curve(4) = {out[2]};
Physical Surface(0) = {out[1]};
