// One-piece intraocular lens with two haptics, C-loop (haptic_type = 0,
// the default) or modified-L (haptic_type = 1), flat in z = 0: the
// mid-surface of the shell. Units: mm. The optic's thickness profile
// and the haptics' thickness are set in the prm (Material/Thickness as a
// function of region and position), not here.
//
// C-loop: each haptic's centre line is a circular arc of radius
// haptic_radius whose farthest point from the lens centre lies on the x
// axis, the haptic's outer edge there at overall_diameter / 2 (the second
// haptic is the first turned by 180 degrees). The arc starts where it
// crosses the optic rim and runs tip_sweep degrees past its farthest
// point.
//
// Modified-L: a straight leg leaves the optic, a knee (a circular fillet
// of centre-line radius knee_radius) turns it by knee_angle degrees, and a
// long arm follows, a circular arc of radius arm_radius whose farthest
// point lies on the x axis at overall_diameter / 2 (outer edge), from
// arm_start degrees (about the arm's centre) to tip_sweep past that point.
// The leg is tangent to the knee and the knee to the arm; the leg runs
// back from the knee until it crosses the optic rim. With the defaults
// the leg leaves the optic nearly radially, 1.7 mm long, and the arm
// runs 85 degrees round the optic: the short leg and long arm of an L
// whose corner is rounded, where the C-loop bends evenly all the way.
//
// Change any constant with Mesh/Gmsh parameters in the prm (e.g.
// "haptic_width = 0.5, haptic_type = 1").
//
// Junction fillet: where a haptic's edge meets the optic's rim the
// outline has a re-entrant corner, whose strain a shell cannot resolve (it
// grows as the mesh is refined). junction_fillet > 0 rounds each corner by
// an arc of that radius, tangent to the rim and to the haptic's edge. The
// fillet is haptic material. Its boundary with the optic leaves the rim
// along the radius at each fillet's tangent point, junction_fillet deep,
// and runs straight across between the two: were it the rim itself, it
// would meet the fillet arc tangentially and leave triangles with a
// vanishing angle there. So the haptic's root takes a foot of the optic.
//
// Junction refinement: junction_mesh_size > 0 (mm at level 0) meshes the
// lens with triangles of that size within junction_mesh_radius of each
// junction's fillet (of each corner when sharp), growing beyond, so that
// the strain there can be converged without refining the whole lens.
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
  haptics_only = 0,        // 1: one haptic alone, for its compression test
  haptic_type = 0,         // 0: C-loop, 1: modified-L
  knee_radius = 0.6,       // mm, modified-L: centre-line radius of the knee
  knee_angle = 90,         // degrees, modified-L: turn of the knee
  arm_radius = 4.5,        // mm, modified-L: radius of the arm's centre line
  arm_start = -70,         // degrees, modified-L: the arm's start about its centre
  junction_fillet = 0,     // mm, radius of a fillet where each haptic edge meets the optic rim (0: a sharp corner)
  junction_mesh_size = 0,  // mm at level 0, triangles near each junction (0: no local refinement)
  junction_mesh_radius = 0.15 // mm, how far from each junction's fillet (or corner) junction_mesh_size holds
];

scale = 2^(-refinement_level);
tip_angle = tip_sweep * Pi / 180;
If (haptic_type != 0 && haptic_type != 1)
  Error("lens.geo: haptic_type = %g; it must be 0 (C-loop) or 1 (modified-L)", haptic_type);
EndIf
// Checked before any geometry is built: gmsh goes on after an Error.
If (junction_mesh_size < 0 || junction_mesh_radius <= 0)
  Error("lens.geo: junction_mesh_size = %g mm must be >= 0 and junction_mesh_radius = %g mm > 0", junction_mesh_size, junction_mesh_radius);
EndIf
If (junction_mesh_size >= optic_mesh_size)
  Error("lens.geo: junction_mesh_size = %g mm must be below optic_mesh_size = %g mm: it refines the junctions", junction_mesh_size, optic_mesh_size);
EndIf
If (junction_mesh_size > 0 && haptics_only)
  Error("lens.geo: junction_mesh_size refines the haptic-optic junctions, which haptics_only = 1 leaves out");
EndIf
If (haptic_type == 0)
// Arc centre (rho, 0): the haptic's outer edge reaches overall_diameter / 2.
rho = overall_diameter / 2 - haptic_width / 2 - haptic_radius;
If (rho <= 0 || rho + optic_radius <= haptic_radius || haptic_radius - rho >= optic_radius)
  Error("lens.geo: the haptic arc (radius %g) does not cross the optic rim (radius %g)", haptic_radius, optic_radius);
EndIf
// Angle about the arc centre where the centre line crosses the optic rim.
root_angle = -Acos((optic_radius^2 - rho^2 - haptic_radius^2) / (2 * haptic_radius * rho));
// The strip of the lens reaches 0.6 mm into the optic and is cut there.
start_angle = root_angle - (1 - haptics_only) * 0.6 / haptic_radius;
EndIf

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

// Modified-L haptic as one surface bounded by its two offset outlines:
// leg (straight), knee (about (kx, ky)), arm (about (arm_centre, 0), split
// at mid angle), the square tip and the square root. Sets sector,
// root_curve, tip_curve and the tip's centre (tip_x, tip_y).
Macro ModifiedLOutline
  If (knee_radius <= haptic_width / 2 || knee_angle <= 0 || knee_angle >= 180)
    Error("lens.geo: the knee needs knee_radius (%g) above half the haptic width (%g) and 0 < knee_angle (%g) < 180", knee_radius, haptic_width / 2, knee_angle);
  EndIf
  arm_centre = overall_diameter / 2 - haptic_width / 2 - arm_radius;
  beta = arm_start * Pi / 180;
  If (arm_radius <= knee_radius || beta >= tip_angle)
    Error("lens.geo: the arm (radius %g, from %g degrees) must be wider than the knee and start before its tip", arm_radius, arm_start);
  EndIf
  // The knee ends where the arm starts, with the arm's tangent; its
  // centre lies on the arm's radius through that point.
  kx = arm_centre + (arm_radius - knee_radius) * Cos(beta);
  ky = (arm_radius - knee_radius) * Sin(beta);
  gamma = beta - knee_angle * Pi / 180;
  // The knee's start and the leg's direction (the knee's tangent there).
  k0x = kx + knee_radius * Cos(gamma); k0y = ky + knee_radius * Sin(gamma);
  dx = -Sin(gamma); dy = Cos(gamma);
  // Back along the leg, |K0 - s d| = optic_radius at s = b - sqrt(b^2 - cq).
  b = k0x * dx + k0y * dy; cq = k0x^2 + k0y^2 - optic_radius^2;
  If (cq <= 0 || b <= 0 || b^2 < cq)
    Error("lens.geo: the modified-L leg (knee at %g, %g) does not cross the optic rim (radius %g)", k0x, k0y, optic_radius);
  EndIf
  leg = b - Sqrt(b^2 - cq) + (1 - haptics_only) * 0.6;
  h = haptic_width / 2;
  // Points on the outline: inner side (towards the turns' centres) and
  // outer side, at the root, the knee's start, the arm's start, the arm's
  // middle and the tip.
  For side In {0:1}
    sg = 1 - 2 * side; // +1 inner, -1 outer
    rt[side] = newp; Point(rt[side]) = {k0x - leg * dx - sg * h * dy, k0y - leg * dy + sg * h * dx, 0};
    ks[side] = newp; Point(ks[side]) = {kx + (knee_radius - sg * h) * Cos(gamma), ky + (knee_radius - sg * h) * Sin(gamma), 0};
    am[side] = newp; Point(am[side]) = {arm_centre + (arm_radius - sg * h) * Cos(beta), (arm_radius - sg * h) * Sin(beta), 0};
    mid = (beta + tip_angle) / 2;
    mm[side] = newp; Point(mm[side]) = {arm_centre + (arm_radius - sg * h) * Cos(mid), (arm_radius - sg * h) * Sin(mid), 0};
    tp[side] = newp; Point(tp[side]) = {arm_centre + (arm_radius - sg * h) * Cos(tip_angle), (arm_radius - sg * h) * Sin(tip_angle), 0};
  EndFor
  pk = newp; Point(pk) = {kx, ky, 0};
  pa = newp; Point(pa) = {arm_centre, 0, 0};
  c[0] = newl; Line(c[0]) = {rt[1], ks[1]};
  c[1] = newl; Circle(c[1]) = {ks[1], pk, am[1]};
  c[2] = newl; Circle(c[2]) = {am[1], pa, mm[1]};
  c[3] = newl; Circle(c[3]) = {mm[1], pa, tp[1]};
  c[4] = newl; Line(c[4]) = {tp[1], tp[0]};
  c[5] = newl; Circle(c[5]) = {tp[0], pa, mm[0]};
  c[6] = newl; Circle(c[6]) = {mm[0], pa, am[0]};
  c[7] = newl; Circle(c[7]) = {am[0], pk, ks[0]};
  c[8] = newl; Line(c[8]) = {ks[0], rt[0]};
  c[9] = newl; Line(c[9]) = {rt[0], rt[1]};
  loop = newll; Curve Loop(loop) = {c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7], c[8], c[9]};
  sector = news; Plane Surface(sector) = {loop};
  root_curve = c[9]; tip_curve = c[4];
  tip_x = arm_centre + arm_radius * Cos(tip_angle); tip_y = arm_radius * Sin(tip_angle);
Return

// The fillet at one junction of the first haptic, on its side k = 0
// (inner edge of the C-loop, or the leg's side towards the knee's centre)
// or k = 1. Sets the fillet's centre (px[k], py[k]), at junction_fillet
// from the edge and optic_radius + junction_fillet from the lens centre;
// its tangent points on the rim (tx[k], ty[k]) and on the edge (ex[k],
// ey[k]). With junction_fillet = 0 the centre is the sharp corner.
Macro JunctionFillet
  f = junction_fillet; R = optic_radius; side = 2 * k - 1;
  If (haptic_type == 0)
    // The edge is the circle of radius re about (rho, 0); the fillet lies
    // outside it on the outer edge and inside it on the inner edge.
    re = haptic_radius + side * haptic_width / 2;
    dh = re + side * f;
    px[k] = ((R + f)^2 - dh^2 + rho^2) / (2 * rho);
    If ((R + f)^2 <= px[k]^2 || dh <= 0)
      Error("lens.geo: no junction fillet of radius %g fits the C-loop's edge (radius %g) at the optic rim", f, re);
    EndIf
    py[k] = -Sqrt((R + f)^2 - px[k]^2);
    ex[k] = rho + (px[k] - rho) * re / dh; ey[k] = py[k] * re / dh;
  Else
    // The edge is the leg's side line k0 + s d + sg h n, n = (-dy, dx),
    // sg = +1 towards the knee's centre; the fillet lies beyond it.
    sg = -side;
    qx = k0x - sg * (h + f) * dy; qy = k0y + sg * (h + f) * dx;
    qd = qx * dx + qy * dy;
    If (qd^2 - qx^2 - qy^2 + (R + f)^2 <= 0)
      Error("lens.geo: no junction fillet of radius %g fits the modified-L leg at the optic rim", f);
    EndIf
    s = -qd + Sqrt(qd^2 - qx^2 - qy^2 + (R + f)^2);
    If (s >= 0)
      Error("lens.geo: a junction fillet of radius %g reaches past the modified-L leg into its knee", f);
    EndIf
    px[k] = qx + s * dx; py[k] = qy + s * dy;
    ex[k] = px[k] + sg * f * dy; ey[k] = py[k] - sg * f * dx;
  EndIf
  tx[k] = px[k] * R / (R + f); ty[k] = py[k] * R / (R + f);
Return

// Local refinement at the four haptic-optic junctions, where the fold's
// strain peaks: triangles of junction_mesh_size within
// junction_mesh_radius of each junction's fillet (of the corner itself
// when junction_fillet = 0; the second haptic's are the first's turned by
// 180 degrees), growing as fast as the distance beyond, so that a
// refinement study can resolve the junction without refining the whole
// lens. The sizes set on the points still hold where they are smaller.
Macro JunctionRefinement
  For k In {0:1}
    Call JunctionFillet;
  EndFor
  // Distance to the nearest fillet's disk (centre (px, py), radius f).
  to_fillets = "min(min(Sqrt((x-(%.10g))^2+(y-(%.10g))^2), Sqrt((x+(%.10g))^2+(y+(%.10g))^2)), min(Sqrt((x-(%.10g))^2+(y-(%.10g))^2), Sqrt((x+(%.10g))^2+(y+(%.10g))^2))) - %.10g";
  Field[1] = MathEval;
  Field[1].F = Sprintf(to_fillets, px[0], py[0], px[0], py[0], px[1], py[1], px[1], py[1], junction_fillet);
  Field[2] = Threshold;
  Field[2].InField = 1;
  Field[2].SizeMin = junction_mesh_size * scale;
  Field[2].SizeMax = optic_mesh_size * scale;
  Field[2].DistMin = junction_mesh_radius;
  Field[2].DistMax = junction_mesh_radius + (optic_mesh_size - junction_mesh_size) * scale;
  Background Field = 2;
Return

// The first haptic's root with both fillets, one face: the two fillets,
// the haptic up to a cut square across it through the farther of the two
// edge tangent points, and a foot inside the optic, from each rim tangent
// point junction_fillet deep along the radius and straight across. The
// haptic is cut beyond both fillets so that the corners, filled, leave no
// vertex behind: at the old obtuse corner the fillet is short, and a
// vertex there would leave slivers.
Macro HapticRoot
  For k In {0:1}
    Call JunctionFillet;
    // How far along the haptic, towards its tip, the edge tangent point lies.
    If (haptic_type == 0)
      along[k] = Atan2(ey[k], ex[k] - rho);
    Else
      along[k] = (ex[k] - k0x) * dx + (ey[k] - k0y) * dy;
    EndIf
  EndFor
  far = (along[1] > along[0]) ? 1 : 0; near = 1 - far;
  // The cut's point (xx, xy) on the near side's edge.
  If (haptic_type == 0)
    re_near = haptic_radius + (2 * near - 1) * haptic_width / 2;
    re_far = haptic_radius + (2 * far - 1) * haptic_width / 2;
    xx = rho + (ex[far] - rho) * re_near / re_far; xy = ey[far] * re_near / re_far;
  Else
    sg_near = 1 - 2 * near;
    xx = ex[far] - 2 * sg_near * h * dy; xy = ey[far] + 2 * sg_near * h * dx;
  EndIf
  For k In {0:1}
    fpt[k] = newp; Point(fpt[k]) = {tx[k], ty[k], 0};
    fpe[k] = newp; Point(fpe[k]) = {ex[k], ey[k], 0};
    fpf[k] = newp; Point(fpf[k]) = {px[k], py[k], 0};
    fpm[k] = newp; Point(fpm[k]) = {tx[k] * (1 - f / R), ty[k] * (1 - f / R), 0};
  EndFor
  cut = newp; Point(cut) = {xx, xy, 0};
  // Round the outline from the rim tangent point of side 0.
  rootline[] = {};
  l = newl; Circle(l) = {fpt[0], fpf[0], fpe[0]}; rootline[] += l;
  first = (far == 0) ? fpe[0] : cut; last = (far == 0) ? cut : fpe[1];
  If (far == 1)
    edge_from = fpe[0]; edge_to = cut; Call NearEdge;
  EndIf
  l = newl; Line(l) = {first, last}; rootline[] += l;
  If (far == 0)
    edge_from = cut; edge_to = fpe[1]; Call NearEdge;
  EndIf
  l = newl; Circle(l) = {fpe[1], fpf[1], fpt[1]}; rootline[] += l;
  l = newl; Line(l) = {fpt[1], fpm[1]}; rootline[] += l;
  l = newl; Line(l) = {fpm[1], fpm[0]}; rootline[] += l;
  l = newl; Line(l) = {fpm[0], fpt[0]}; rootline[] += l;
  loop = newll; Curve Loop(loop) = {rootline[]};
  root = news; Plane Surface(root) = {loop};
Return

// The near side's edge between its fillet and the cut, from edge_from to
// edge_to (side 0: its tangent point to the cut; side 1: the reverse).
Macro NearEdge
  l = newl;
  If (haptic_type == 0)
    ph = newp; Point(ph) = {rho, 0, 0}; Circle(l) = {edge_from, ph, edge_to};
  Else
    Line(l) = {edge_from, edge_to};
  EndIf
  rootline[] += l;
Return

If (haptic_type == 0)
  a0 = start_angle; a1 = tip_angle;
  r0 = haptic_radius - haptic_width / 2; r1 = haptic_radius + haptic_width / 2;
  Call AnnularSector;
  root_curve = c[5]; tip_curve = c[2];
  tip_x = rho + haptic_radius * Cos(tip_angle); tip_y = haptic_radius * Sin(tip_angle);
Else
  Call ModifiedLOutline;
EndIf

If (haptics_only)
  Physical Curve("root", 1) = {root_curve};
  Physical Curve("tip", 2) = {tip_curve};
  Physical Surface("haptic", 2) = {sector};
  MeshSize{PointsOf{Surface{sector};}} = haptic_mesh_size * scale;
Else
  If (junction_fillet <= 0)
    // A round tip, then the second haptic, then the optic, made conforming.
    cap = news; Disk(cap) = {tip_x, tip_y, 0, haptic_width / 2};
    haptic() = BooleanUnion{ Surface{sector}; Delete; }{ Surface{cap}; Delete; };
    second() = Rotate{{0, 0, 1}, {0, 0, 0}, Pi}{ Duplicata{ Surface{haptic(0)}; } };
    optic = news; Disk(optic) = {0, 0, 0, optic_radius};
    tool = news; Disk(tool) = {0, 0, 0, optic_radius};
    outside() = BooleanDifference{ Surface{haptic(0), second(0)}; Delete; }{ Surface{tool}; Delete; };
    pieces() = BooleanFragments{ Surface{optic}; Delete; }{ Surface{outside()}; Delete; };
    inner() = Surface In BoundingBox{-optic_radius - 1e-6, -optic_radius - 1e-6, -1, optic_radius + 1e-6, optic_radius + 1e-6, 1};
  Else
    // As above, but the haptic outside the optic takes its root with the
    // two fillets before it is copied, and the optic gives up the root's
    // foot. A union of faces that only touch keeps them apart, so the
    // haptic is a list of faces, made conforming by the fragments.
    cap = news; Disk(cap) = {tip_x, tip_y, 0, haptic_width / 2};
    haptic() = BooleanUnion{ Surface{sector}; Delete; }{ Surface{cap}; Delete; };
    Call HapticRoot;
    tool = news; Disk(tool) = {0, 0, 0, optic_radius};
    haptic() = BooleanDifference{ Surface{haptic(0)}; Delete; }{ Surface{tool, root}; };
    Recursive Delete{ Surface{tool}; }
    haptic() += root;
    second() = Rotate{{0, 0, 1}, {0, 0, 0}, Pi}{ Duplicata{ Surface{haptic()}; } };
    optic = news; Disk(optic) = {0, 0, 0, optic_radius};
    optic() = BooleanDifference{ Surface{optic}; Delete; }{ Surface{haptic(), second()}; };
    pieces() = BooleanFragments{ Surface{optic()}; Delete; }{ Surface{haptic(), second()}; Delete; };
    // The fragments split no face here, so the optic keeps its tag.
    inner() = optic();
  EndIf
  Physical Surface("optic", 1) = {inner()};
  Physical Surface("haptics", 2) = {pieces()};
  Physical Surface("haptics", 2) -= {inner()};
  MeshSize{PointsOf{Surface{pieces()};}} = haptic_mesh_size * scale;
  MeshSize{PointsOf{Surface{inner()};}} = optic_mesh_size * scale;
EndIf
If (junction_mesh_size > 0 && !haptics_only)
  Call JunctionRefinement;
EndIf
Mesh.MeshSizeExtendFromBoundary = 1;
Mesh.Algorithm = 6;
