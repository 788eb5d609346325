// A rigid partial cylinder (length units of the scene): axis along y
// through the origin, from y = -0.5 to y = width - 0.5, radius R, the
// arc from first_angle to last_angle (degrees from +x towards +z) cut
// into facets of facet_angle degrees. A faceted cylinder lies inside the
// true one by R (1 - cos(facet_angle / 2)): 1e-5 R at the default
// 0.5 degrees.
DefineConstant[
  R = {2, Name "radius"},
  width = {2, Name "length along the axis"},
  first_angle = {100, Name "first angle (degrees)"},
  last_angle = {-20, Name "last angle (degrees)"},
  facet_angle = {0.5, Name "facet angle (degrees)"}
];
Point(1) = {0, -0.5, 0};
// Gmsh arcs must stay below 180 degrees: the arc is cut in two halves.
middle_angle = (first_angle + last_angle) / 2;
angles[] = {first_angle, middle_angle, last_angle};
For k In {0:2}
  Point(2 + k) = {R * Cos(angles[k] * Pi / 180), -0.5,
                  R * Sin(angles[k] * Pi / 180)};
EndFor
Circle(1) = {2, 1, 3};
Circle(2) = {3, 1, 4};
facets = Ceil(Fabs(first_angle - last_angle) / (2 * facet_angle));
Transfinite Curve {1, 2} = facets + 1;
surfaces[] = {};
For arc In {1:2}
  out[] = Extrude {0, width, 0} { Curve{arc}; Layers{1}; };
  surfaces[] += out[1];
EndFor
Physical Surface(1) = {surfaces[]};
