// Two squares, one above the other, as one shell mesh (two
// connected pieces): the lower in z = 0 (physical surface 1, its edges
// physical curve 1), the upper in z = upper_height (physical surface 2,
// edges physical curve 2), meshed independently (non-matching), each
// with vertices at (5, 5) and (8, 5). The upper square is [0, 10]^2, the
// lower one lower_margin larger on every side. Units: those of the scene (here mm).
DefineConstant[
  refinement_level = 0,
  upper_height = 0.0555,  // mid-surface to mid-surface
  lower_size = 0.5,       // element size of the lower plate at level 0
  upper_size = 0.7,       // element size of the upper plate at level 0
  lower_margin = 0        // the lower plate reaches this far beyond the
                          // upper one on every side
];
scale = 2^(-refinement_level);
For k In {0:1}
  z = k * upper_height;
  size = (k == 0 ? lower_size : upper_size) * scale;
  m = (k == 0 ? lower_margin : 0);
  p0 = newp; Point(p0) = {-m, -m, z, size};
  p1 = newp; Point(p1) = {10 + m, -m, z, size};
  p2 = newp; Point(p2) = {10 + m, 10 + m, z, size};
  p3 = newp; Point(p3) = {-m, 10 + m, z, size};
  pc = newp; Point(pc) = {5, 5, z, size};
  pe = newp; Point(pe) = {8, 5, z, size};
  l0 = newl; Line(l0) = {p0, p1};
  l1 = newl; Line(l1) = {p1, p2};
  l2 = newl; Line(l2) = {p2, p3};
  l3 = newl; Line(l3) = {p3, p0};
  loop = newll; Curve Loop(loop) = {l0, l1, l2, l3};
  s = news; Plane Surface(s) = {loop};
  Point{pc, pe} In Surface{s};
  Physical Curve(k + 1) = {l0, l1, l2, l3};
  Physical Surface(k + 1) = {s};
EndFor
Mesh.Algorithm = 6;
