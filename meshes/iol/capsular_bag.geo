// The capsular bag of the IOL scene, a rigid ellipsoidal surface (units:
// mm): equator of diameter 2 * equator_radius in the plane z = 0, polar
// semi-axis polar_radius along z, centred at the origin, with a circular
// opening of radius opening_radius about the -x axis where the nozzle
// enters (the prm places the bag beyond the nozzle's tip).
SetFactory("OpenCASCADE");
DefineConstant[
  refinement_level = 0,
  equator_radius = 5.0,   // mm
  polar_radius = 2.25,    // mm
  opening_radius = 1.9,   // mm
  mesh_size = 0.6         // mm at level 0
];
If (!(opening_radius < polar_radius && polar_radius > 0))
  Error("capsular_bag.geo: need 0 < opening_radius < polar_radius");
EndIf
Sphere(1) = {0, 0, 0, 1};
Dilate {{0, 0, 0}, {equator_radius, equator_radius, polar_radius}} { Volume{1}; }
// The cutter reaches from outside to x = -0.4 equator_radius, past the
// opening's rim on the ellipsoid and short of its far side.
Cylinder(2) = {-2 * equator_radius, 0, 0, 1.6 * equator_radius, 0, 0, opening_radius};
BooleanDifference(3) = { Volume{1}; Delete; }{ Volume{2}; Delete; };
bag[] = Boundary{ Volume{3}; };
// Keep the ellipsoid, drop the opening's cylindrical wall: the faces
// whose bounding box reaches past the opening into the bag's inside.
faces[] = {};
For k In {0:#bag[] - 1}
  box[] = BoundingBox Surface{bag[k]};
  If (box[3] - box[0] > equator_radius)
    faces[] += bag[k];
  EndIf
EndFor
Physical Surface("capsular bag", 1) = {faces[]};
MeshSize{ PointsOf{ Volume{3}; } } = mesh_size * 2^(-refinement_level);
Mesh.MeshSizeFromCurvature = 12;
