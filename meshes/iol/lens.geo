// One-piece intraocular lens with two C-loop haptics, flat in z = 0:
// the mid-surface of the shell. Units: mm. The optic's thickness profile
// and the haptics' thickness are set in the prm (Material/Thickness as a
// function of region and position), not here.
//
// Each haptic's centre line is a circular arc of radius haptic_radius
// whose farthest point from the lens centre lies on the x axis, the
// haptic's outer edge there at overall_diameter / 2 (the second haptic is the first turned by 180 degrees).
// The arc starts where it crosses the optic rim and runs tip_sweep
// degrees past its farthest point. Change any constant with
// Mesh/Gmsh parameters in the prm (e.g. "haptic_width = 0.5").
//
// Physical groups: surface 1 optic, surface 2 haptics. With
// haptics_only = 1 the file instead holds one haptic without the optic,
// cut square at its root (physical curve 1) and at its tip (curve 2): the
// single-haptic compression test clamps the root and loads the tip.
SetFactory("OpenCASCADE");

DefineConstant[
  refinement_level = 0,    // each level halves the mesh size
  optic_radius = 3.0,      // mm
  overall_diameter = 13.0, // mm, haptic tip to haptic tip
  haptic_width = 0.4,      // mm, in the lens plane
  haptic_radius = 3.8,     // mm, radius of the haptic's centre line
  tip_sweep = 15,          // degrees past the farthest point
  optic_mesh_size = 0.55,  // mm, at level 0
  haptic_mesh_size = 0.22, // mm, at level 0
  haptics_only = 0         // 1: one haptic alone, for its compression test
];

scale = 2^(-refinement_level);
// Arc centre (rho, 0): the haptic's outer edge reaches overall_diameter / 2.
rho = overall_diameter / 2 - haptic_width / 2 - haptic_radius;
If (rho <= 0 || rho + optic_radius <= haptic_radius || haptic_radius - rho >= optic_radius)
  Error("lens.geo: the haptic arc (radius %g) does not cross the optic rim (radius %g)", haptic_radius, optic_radius);
EndIf
// Angle about the arc centre where the centre line crosses the optic rim.
root_angle = -Acos((optic_radius^2 - rho^2 - haptic_radius^2) / (2 * haptic_radius * rho));
tip_angle = tip_sweep * Pi / 180;
// The strip of the lens reaches 0.6 mm into the optic and is cut there.
start_angle = root_angle - (1 - haptics_only) * 0.6 / haptic_radius;

// Annular sector about (rho, 0) from angle a0 to a1, radii r0 < r1, split
// at mid angle so that every arc stays below 180 degrees.
Macro AnnularSector
  pc = newp; Point(pc) = {rho, 0, 0};
  For k In {0:2}
    a = a0 + k * (a1 - a0) / 2;
    pi[k] = newp; Point(pi[k]) = {rho + r0 * Cos(a), r0 * Sin(a), 0};
    po[k] = newp; Point(po[k]) = {rho + r1 * Cos(a), r1 * Sin(a), 0};
  EndFor
  c[0] = newl; Circle(c[0]) = {po[0], pc, po[1]};
  c[1] = newl; Circle(c[1]) = {po[1], pc, po[2]};
  c[2] = newl; Line(c[2]) = {po[2], pi[2]};
  c[3] = newl; Circle(c[3]) = {pi[2], pc, pi[1]};
  c[4] = newl; Circle(c[4]) = {pi[1], pc, pi[0]};
  c[5] = newl; Line(c[5]) = {pi[0], po[0]};
  loop = newll; Curve Loop(loop) = {c[0], c[1], c[2], c[3], c[4], c[5]};
  sector = news; Plane Surface(sector) = {loop};
Return

a0 = start_angle; a1 = tip_angle;
r0 = haptic_radius - haptic_width / 2; r1 = haptic_radius + haptic_width / 2;
Call AnnularSector;

If (haptics_only)
  Physical Curve("root", 1) = {c[5]};
  Physical Curve("tip", 2) = {c[2]};
  Physical Surface("haptic", 2) = {sector};
  MeshSize{PointsOf{Surface{sector};}} = haptic_mesh_size * scale;
Else
  // A round tip, then the second haptic, then the optic, made conforming.
  cap = news; Disk(cap) = {rho + haptic_radius * Cos(tip_angle), haptic_radius * Sin(tip_angle), 0, haptic_width / 2};
  haptic() = BooleanUnion{ Surface{sector}; Delete; }{ Surface{cap}; Delete; };
  second() = Rotate{{0, 0, 1}, {0, 0, 0}, Pi}{ Duplicata{ Surface{haptic(0)}; } };
  optic = news; Disk(optic) = {0, 0, 0, optic_radius};
  tool = news; Disk(tool) = {0, 0, 0, optic_radius};
  outside() = BooleanDifference{ Surface{haptic(0), second(0)}; Delete; }{ Surface{tool}; Delete; };
  pieces() = BooleanFragments{ Surface{optic}; Delete; }{ Surface{outside()}; Delete; };
  inner() = Surface In BoundingBox{-optic_radius - 1e-6, -optic_radius - 1e-6, -1, optic_radius + 1e-6, optic_radius + 1e-6, 1};
  Physical Surface("optic", 1) = {inner()};
  Physical Surface("haptics", 2) = {pieces()};
  Physical Surface("haptics", 2) -= {inner()};
  MeshSize{PointsOf{Surface{pieces()};}} = haptic_mesh_size * scale;
  MeshSize{PointsOf{Surface{inner()};}} = optic_mesh_size * scale;
EndIf
Mesh.MeshSizeExtendFromBoundary = 1;
Mesh.Algorithm = 6;
