// A rigid plunger along the x axis: a flat face of radius plunger_radius
// at x = 0 facing +x, on a rod of the same radius reaching back
// plunger_length to x = -plunger_length (mm). Used by the funnel scene
// and the IOL injection (prm/iol/injection.prm).
DefineConstant[
  plunger_radius = 1.35,  // mm
  plunger_length = 3.0,   // mm
  mesh_size = 0.3         // mm
];
lc = mesh_size;
Point(1) = {0, 0, 0, lc};
Point(2) = {0, plunger_radius, 0, lc};
Point(3) = {-plunger_length, plunger_radius, 0, lc};
Line(1) = {1, 2};
Line(2) = {2, 3};
surfaces[] = {};
For profile In {1:2}
  line = profile;
  For quarter In {1:4}
    out[] = Extrude {{1, 0, 0}, {0, 0, 0}, Pi / 2} { Line{line}; };
    line = out[0];
    surfaces[] += out[1];
  EndFor
EndFor
Physical Surface(1) = {surfaces[]};
