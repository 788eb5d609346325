// A rigid plunger along the x axis: a flat face of radius plunger_radius
// at x = 0 facing +x, on a rod of the same radius reaching back
// plunger_length to x = -plunger_length (mm). Used by the funnel scene
// and the IOL injection (prm/iol/injection.prm). With along_y = 1 the
// same rod is turned by 90 degrees about z: along y, its face at y = 0
// facing +y. A rod that must turn about y as well (the mandrels of
// prm/iol/tuck.prm, which bend with the optic) then needs one rotation.
DefineConstant[
  plunger_radius = 1.35,  // mm
  plunger_length = 3.0,   // mm
  mesh_size = 0.3,        // mm
  along_y = 0             // 1: along y instead of x (a flag)
];
lc = mesh_size;
// (a, b) is where the rod's axis points, in the xy plane; (-b, a) is
// the radial direction of the profile.
a = 1 - along_y;
b = along_y;
Point(1) = {0, 0, 0, lc};
Point(2) = {-b * plunger_radius, a * plunger_radius, 0, lc};
Point(3) = {-a * plunger_length - b * plunger_radius,
            -b * plunger_length + a * plunger_radius, 0, lc};
Line(1) = {1, 2};
Line(2) = {2, 3};
surfaces[] = {};
For profile In {1:2}
  line = profile;
  For quarter In {1:4}
    out[] = Extrude {{a, b, 0}, {0, 0, 0}, Pi / 2} { Line{line}; };
    line = out[0];
    surfaces[] += out[1];
  EndFor
EndFor
Physical Surface(1) = {surfaces[]};
