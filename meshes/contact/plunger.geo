// A rigid plunger along the x axis: a flat face of radius 1.35 at x = 0
// facing +x, on a rod of the same radius reaching back to x = -3 (mm).
lc = 0.3;
Point(1) = {0, 0, 0, lc};
Point(2) = {0, 1.35, 0, lc};
Point(3) = {-3, 1.35, 0, lc};
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
