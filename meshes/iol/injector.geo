// The injector cartridge of the IOL scene, a rigid surface about the x
// axis (units: mm). A loading chamber of elliptical cross-section
// (half-width chamber_half_width along y, half-height chamber_half_height
// along z) from x = chamber_start to taper_start; a lofted taper turns the
// ellipse into the nozzle's circle (inner radius nozzle_radius) at
// taper_end; the nozzle runs to nozzle_tip, where its lip (wall thickness
// nozzle_wall) turns back over lip_length on the outside. Every constant
// can be set from the prm (Gmsh parameters).
// prm/iol/injection.prm makes the chamber a circular tube of the folding
// wings' radius (chamber_half_width = chamber_half_height = 2) that takes
// the lens already folded by the wings. The defaults below are a flat
// chamber whose taper would fold the lens as it is pushed: the lens jams
// in it, which is why the scene folds with wings
// (doc/validation/iol-injection.md, "Why wings and not a taper").
SetFactory("OpenCASCADE");
DefineConstant[
  refinement_level = 0,
  chamber_start = -8.0,      // mm
  taper_start = 4.0,         // mm
  taper_end = 10.0,          // mm
  nozzle_tip = 13.5,         // mm
  chamber_half_width = 5.0,  // mm, inner
  chamber_half_height = 1.2, // mm, inner
  nozzle_radius = 1.5,       // mm, inner (the tip's inner diameter is twice this)
  nozzle_wall = 0.25,        // mm
  lip_length = 1.5,          // mm
  mesh_size = 0.5,           // mm at level 0, on the chamber; finer in the nozzle
  haptic_thickness = 0.45    // mm, of the lens to pass: the nozzle must be wider than twice it
];
If (!(chamber_start < taper_start && taper_start < taper_end && taper_end < nozzle_tip))
  Error("injector.geo: need chamber_start < taper_start < taper_end < nozzle_tip");
EndIf
If (!(nozzle_radius > 0 && nozzle_radius < chamber_half_width && nozzle_wall > 0 && chamber_half_height > 0 && chamber_half_height <= chamber_half_width))
  Error("injector.geo: need 0 < nozzle_radius < chamber_half_width, 0 < chamber_half_height <= chamber_half_width and nozzle_wall > 0");
EndIf
If (2 * nozzle_radius <= 2 * haptic_thickness)
  Error("injector.geo: the nozzle's inner diameter 2 * nozzle_radius = %g mm is not wider than twice the haptic thickness (haptic_thickness = %g mm): a folded haptic cannot pass", 2 * nozzle_radius, haptic_thickness);
EndIf
scale = 2^(-refinement_level);

// A closed curve in the plane x = x0: an ellipse (half-widths a along y,
// b <= a along z) built in the xy plane and turned into place.
Macro SectionEllipse
  section = newc;
  Ellipse(section) = {0, 0, 0, a, b};
  Rotate {{0, 0, 1}, {0, 0, 0}, Pi / 2} { Curve{section}; }
  Rotate {{0, 1, 0}, {0, 0, 0}, Pi / 2} { Curve{section}; }
  Translate {x0, 0, 0} { Curve{section}; }
  wire = newll; Wire(wire) = {section};
Return

a = chamber_half_width; b = chamber_half_height;
x0 = chamber_start;
Call SectionEllipse;
back = wire;
x0 = taper_start;
Call SectionEllipse;
front = wire;
a = nozzle_radius; b = nozzle_radius;
x0 = taper_end;
Call SectionEllipse;
throat = wire;
x0 = nozzle_tip;
Call SectionEllipse;
tip = wire; tip_curve = section;
a = nozzle_radius + nozzle_wall; b = a;
x0 = nozzle_tip;
Call SectionEllipse;
rim = wire; rim_curve = section;
x0 = nozzle_tip - lip_length;
Call SectionEllipse;
outside = wire;
chamber[] = ThruSections{back, front};
taper[] = ThruSections{front, throat};
nozzle[] = ThruSections{throat, tip};
lip_loop_outer = newll; Curve Loop(lip_loop_outer) = {rim_curve};
lip_loop_inner = newll; Curve Loop(lip_loop_inner) = {tip_curve};
lip = news; Plane Surface(lip) = {lip_loop_outer, lip_loop_inner};
outer[] = ThruSections{rim, outside};
faces[] = {chamber[], taper[], nozzle[], lip, outer[]};
Physical Surface("cartridge", 1) = {faces[]};
MeshSize{ PointsOf{ Surface{chamber[], taper[]}; } } = mesh_size * scale;
MeshSize{ PointsOf{ Surface{nozzle[], lip, outer[]}; } } = mesh_size * scale * nozzle_radius / chamber_half_width * 2;
Mesh.MeshSizeFromCurvature = 0;
