// One clamp of the ISO 11979-3 compression test: a concave cylindrical
// face (axis z) of radius clamp_radius about the origin, spanning
// +-clamp_half_angle about the +x axis and clamp_height in z, facing the
// lens at the origin. The prm moves it along x and turns the second clamp
// by 180 degrees about z. Units: mm. A rigid obstacle: only its surface.
SetFactory("OpenCASCADE");
DefineConstant[
  refinement_level = 0,
  clamp_radius = 5.0,      // mm; the prm adds half the haptic thickness
  clamp_half_angle = 50,   // degrees
  clamp_height = 2.0,      // mm
  clamp_mesh_size = 0.35   // mm
];
angle = clamp_half_angle * Pi / 180;
Circle(1) = {0, 0, -clamp_height / 2, clamp_radius, -angle, angle};
face[] = Extrude{0, 0, clamp_height}{ Curve{1}; };
Physical Surface("clamp", 1) = {face[1]};
MeshSize{PointsOf{Surface{face[1]};}} = clamp_mesh_size * 2^(-refinement_level);
Mesh.MeshSizeExtendFromBoundary = 1;
