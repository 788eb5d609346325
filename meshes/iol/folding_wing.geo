// One folding wing of the IOL cartridge's loading chamber, a rigid half
// cylinder (units: mm): radius wing_radius about the x axis, from
// x = wing_start to wing_end, spanning the side y >= 0 (side = 1) or
// y <= 0 (side = -1) from its bottom line (0, 0, -wing_radius), the hinge,
// to its top line. Closed, the two wings make a tube about the x axis;
// the prm opens each by turning it outwards about its hinge, and closes it
// over the lens lying on the hinge (prm/iol/injection.prm).
SetFactory("OpenCASCADE");
DefineConstant[
  refinement_level = 0,
  wing_radius = 2.0,  // mm, inner
  wing_start = -7.0,  // mm
  wing_end = 7.5,     // mm
  side = 1,           // 1: the y >= 0 wing, -1: the y <= 0 wing
  mesh_size = 0.4     // mm at level 0
];
If (!(wing_radius > 0 && wing_start < wing_end && (side == 1 || side == -1)))
  Error("folding_wing.geo: need wing_radius > 0, wing_start < wing_end and side = 1 or -1");
EndIf
// The arc from the hinge (angle -90 degrees) over the side to the top,
// drawn in the xy plane about the origin and turned into the plane x = 0.
Circle(1) = {0, 0, 0, wing_radius, -Pi / 2, Pi / 2};
Rotate {{0, 1, 0}, {0, 0, 0}, -Pi / 2} { Curve{1}; }  // x -> z: (x, y) -> (0, y, x)
Rotate {{1, 0, 0}, {0, 0, 0}, -Pi / 2} { Curve{1}; }  // bottom of the arc to -z
If (side == -1)  // the mirror image y -> -y (the arc is symmetric in z)
  Rotate {{1, 0, 0}, {0, 0, 0}, Pi } { Curve{1}; }
EndIf
Translate {wing_start, 0, 0} { Curve{1}; }
wing[] = Extrude {wing_end - wing_start, 0, 0} { Curve{1}; };
Physical Surface("wing", 1) = {wing[1]};
MeshSize{ PointsOf{ Surface{wing[1]}; } } = mesh_size * 2^(-refinement_level);
Mesh.MeshSizeFromCurvature = 12;
