// A rigid funnel along the x axis: a cone from radius 4.5 at x = 0 to
// 1.5 at x = 6, then a tube of radius 1.5 to x = 14 (mm).
lc = 0.4;
Point(1) = {0, 4.5, 0, lc};
Point(2) = {6, 1.5, 0, lc};
Point(3) = {14, 1.5, 0, lc};
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
