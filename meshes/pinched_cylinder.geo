// Pinched cylinder with rigid end diaphragms, one eighth (MacNeal & Harder
// 1985): radius 300, axis along y, half length 300; the eighth spans the
// quarter circle from the top (0, 0, 300) to the side (300, 0, 0).
// Physical curves: 1 = mid-length arc (y = 0, symmetry y), 2 = end arc on
// the diaphragm (y = 300), 3 = top line (x = 0, symmetry x), 4 = side line
// (z = 0, symmetry z). The load point is (0, 0, 300).
DefineConstant[ refinement_level = {0, Name "refinement_level"} ];
R = 300;
half_length = 300;
n = 4 * 2^refinement_level;
Point(1) = {0, 0, 0};
Point(2) = {0, 0, R};
Point(3) = {R, 0, 0};
Circle(1) = {2, 1, 3};
Transfinite Curve{1} = n + 1;
out[] = Extrude {0, half_length, 0} { Curve{1}; Layers{n}; };
Physical Curve(1) = {1};
Physical Curve(2) = {out[0]};
Physical Curve(3) = {out[3]};
Physical Curve(4) = {out[2]};
Physical Surface(0) = {out[1]};
