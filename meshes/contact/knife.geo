// A rigid knife: two flat faces meeting at a straight edge along y at
// x = 0, z = 0 (length units of the scene), rising at 45 degrees to
// either side. Each face is one strip of two triangles, so the only
// vertices are at the ends y = -1 and y = length - 1: in between the edge
// meets a shell with no obstacle vertex near it, where only edge-edge
// pairs can hold it.
DefineConstant[ length = {12, Name "edge length"} ];
Point(1) = {0, -1, 0};
Point(2) = {0, length - 1, 0};
Point(3) = {-1, length - 1, 1};
Point(4) = {-1, -1, 1};
Point(5) = {1, -1, 1};
Point(6) = {1, length - 1, 1};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Line(5) = {1, 5};
Line(6) = {5, 6};
Line(7) = {6, 2};
Curve Loop(1) = {1, 2, 3, 4};
Curve Loop(2) = {5, 6, 7, -1};
Plane Surface(1) = {1};
Plane Surface(2) = {2};
Transfinite Curve {1:7} = 2;
Transfinite Surface {1, 2};
Physical Surface(1) = {1, 2};
