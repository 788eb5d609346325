// Hinged cylindrical roof (Sze, Liu & Lo 2004, benchmark 3.6): radius
// R = 2540, half angle 0.1 rad, length 508, cylinder axis along y. The
// straight edges (physical curve 1) are hinged, the curved edges (2) free.
// The apex (0, 254, R(1 - cos 0.1)) is a mesh vertex. Structured triangles;
// each refinement level doubles the divisions in both directions.
DefineConstant[ refinement_level = {0, Name "refinement_level"} ];
R = 2540;
half_angle = 0.1;
length = 508;
n = 8 * 2^refinement_level;
rise = R * (1 - Cos(half_angle));
Point(1) = {0, 0, rise - R};               // centre of curvature
Point(2) = {-R * Sin(half_angle), 0, 0};
Point(3) = {0, 0, rise};
Point(4) = {R * Sin(half_angle), 0, 0};
Circle(1) = {2, 1, 3};
Circle(2) = {3, 1, 4};
Transfinite Curve{1, 2} = n + 1;
left[] = Extrude {0, length, 0} { Curve{1}; Layers{2 * n}; };
right[] = Extrude {0, length, 0} { Curve{2}; Layers{2 * n}; };
// left[0]/right[0]: far curved edges, left[1]/right[1]: surfaces,
// left[3], right[2]: straight edges at x = -+ R sin(0.1) (gmsh lists the
// extruded end point first).
Physical Curve(1) = {left[3], right[2]};
Physical Curve(2) = {1, 2, left[0], right[0]};
Physical Surface(0) = {left[1], right[1]};
