// Pinched hemisphere with an 18 degree hole, one quarter (MacNeal & Harder
// 1985): radius 10, from the equator (z = 0) up to latitude 72 degrees,
// longitudes 0 to 90 degrees. Physical curves: 1 = equator (free),
// 2 = meridian at longitude 0 (y = 0, symmetry y), 3 = meridian at
// longitude 90 (x = 0, symmetry x), 4 = hole edge (free). Loads act at
// (10, 0, 0) and (0, 10, 0). Structured triangles on the sphere.
DefineConstant[ refinement_level = {0, Name "refinement_level"} ];
R = 10;
top = 72 * Pi / 180;
n = 4 * 2^refinement_level;
Point(1) = {0, 0, 0};
Point(2) = {R, 0, 0};
Point(3) = {0, R, 0};
Point(4) = {0, R * Cos(top), R * Sin(top)};
Point(5) = {R * Cos(top), 0, R * Sin(top)};
Point(6) = {0, 0, R * Sin(top)};
Circle(1) = {2, 1, 3};   // equator
Circle(2) = {3, 1, 4};   // meridian x = 0
Circle(3) = {4, 6, 5};   // hole edge
Circle(4) = {5, 1, 2};   // meridian y = 0
Transfinite Curve{1, 2, 3, 4} = n + 1;
Curve Loop(1) = {1, 2, 3, 4};
Surface(1) = {1} In Sphere{1};
Transfinite Surface{1};
Physical Curve(1) = {1};
Physical Curve(2) = {4};
Physical Curve(3) = {2};
Physical Curve(4) = {3};
Physical Surface(0) = {1};
