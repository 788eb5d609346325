// A tucking paddle, the flat blade of the forceps that lays a haptic over
// the optic (prm/iol/tuck.prm; units: mm). A rectangle in the plane
// z = blade_z, from its inner edge x = inner_x outwards over blade_length
// (towards -x for side = -1, +x for side = 1). The lens's two haptics
// are each other turned by 180 degrees about z, and so are the two
// paddles: side = -1 spans y from -y_low to y_high, side = 1 from -y_high
// to y_low.
// The prm turns it by 180 degrees about a line parallel to y above the
// hinge line, which carries the haptic lying on it over the optic.
DefineConstant[
  refinement_level = 0,
  inner_x = -3.8,      // mm, signed: the blade's inner edge
  blade_length = 3.2,  // mm, outwards from the inner edge (3.6 mm blades
                       // meet over the optic:
                       // doc/validation/iol-injection.md,
                       // "The tuck (stage 1)")
  y_low = 1.6,         // mm, how far the side = -1 paddle reaches to -y
  y_high = 4.3,        // mm, how far it reaches to +y
  blade_z = -0.275,    // mm
  side = -1,           // -1: the paddle of the haptic at -x, 1: at +x
  turn = 0,            // degrees: the whole blade turned about the z axis,
                       // for a lens turned so (prm Mesh/Vertex transformation)
  mesh_size = 0.5      // mm at level 0
];
If (!(blade_length > 0 && y_low + y_high > 0 && (side == 1 || side == -1)))
  Error("tucking_paddle.geo: need blade_length > 0, y_low + y_high > 0 and side = 1 or -1");
EndIf
If (side * inner_x < 0)
  Error("tucking_paddle.geo: inner_x = %g lies on the other side (side = %g)", inner_x, side);
EndIf
lc = mesh_size * 2^(-refinement_level);
x_out = inner_x + side * blade_length;
Point(1) = {inner_x, side * y_low, blade_z, lc};
Point(2) = {x_out, side * y_low, blade_z, lc};
Point(3) = {x_out, -side * y_high, blade_z, lc};
Point(4) = {inner_x, -side * y_high, blade_z, lc};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
If (turn != 0)
  Rotate {{0, 0, 1}, {0, 0, 0}, turn * Pi / 180} { Surface{1}; }
EndIf
Physical Surface("paddle", 1) = {1};
