// A flat square obstacle, 30 x 30 (length units of the scene), in z = 0,
// centred on (5, 5): the rigid plane of the contact scenes.
size = 6;
Point(1) = {-10, -10, 0, size};
Point(2) = {20, -10, 0, size};
Point(3) = {20, 20, 0, size};
Point(4) = {-10, 20, 0, size};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Physical Surface(1) = {1};
