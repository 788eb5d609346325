#include <coshell/base/expressions.h>
#include <coshell/mesh/mesh.h>

#include <deal.II/grid/grid_tools.h>

#include <deal.II/base/utilities.h>

#include <cmath>
#include <filesystem>

namespace coshell::mesh
{
  using namespace dealii;

  void MeshParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Mesh");
    prm.declare_entry("Source", "rectangle",
                      Patterns::Selection("rectangle|gmsh"),
                      "Selects where the mesh comes from: rectangle, a "
                      "generated rectangular plate in the z=0 plane "
                      "(boundary ids 0: x=0, 1: x=Lx, 2: y=0, 3: y=Ly), or "
                      "gmsh, the file named by Gmsh file.");
    prm.declare_entry("Gmsh file", "", Patterns::Anything(),
                      "File path of a .msh file (read as is, then refined "
                      "globally per level) or a .geo file (meshed by gmsh "
                      "for each level with the gmsh constant "
                      "refinement_level set to the level). Relative paths "
                      "are tried from the working directory, then from the "
                      "directory of the parameter file. Coordinates in the "
                      "file are in the length unit of the scene (m, mm, "
                      "...).");
    prm.declare_entry("Gmsh parameters", "", Patterns::Anything(),
                      "Constants set when a .geo Gmsh file is meshed, as "
                      "'name = value' entries separated by ',' (gmsh "
                      "-setnumber), overriding the file's DefineConstant "
                      "defaults, e.g. 'haptic_width = 0.5'. Unit: each "
                      "constant's own, as the Gmsh file documents it.");
    prm.declare_entry("Triangle pattern", "crossed",
                      Patterns::Selection("same-diagonal|alternating|crossed"),
                      "Selects how a generated rectangle splits each "
                      "square into triangles (same-diagonal, alternating "
                      "or crossed).");
    prm.declare_entry("Length x", "1", Patterns::Double(0),
                      "Plate length along x; > 0 for Source = rectangle. "
                      "Unit: length (m in SI, mm in the IOL scenes).");
    prm.declare_entry("Length y", "1", Patterns::Double(0),
                      "Plate length along y; > 0 for Source = rectangle. "
                      "Unit: length (m in SI, mm in the IOL scenes).");
    prm.declare_entry("Subdivisions x", "4", Patterns::Integer(1),
                      "Number of squares along x at refinement level 0. "
                      "Unit: dimensionless (a count).");
    prm.declare_entry("Subdivisions y", "4", Patterns::Integer(1),
                      "Number of squares along y at refinement level 0. "
                      "Unit: dimensionless (a count).");
    prm.declare_entry("Refinement levels", "0",
                      Patterns::List(Patterns::Integer(0, 12), 1),
                      "List of refinement levels to run; more than one "
                      "makes a refinement study that writes "
                      "convergence.csv. Each level halves h. Unit: "
                      "dimensionless (level numbers).");
    prm.declare_entry("Normal reference", "0, 0, 1",
                      Patterns::List(Patterns::Double(), 3, 3),
                      "Direction vector x, y, z (only its "
                      "direction matters). Cell normals are made consistent "
                      "across edges and each connected patch is turned to "
                      "face this direction; pressure acts along these "
                      "normals. Unit: dimensionless.");
    prm.declare_entry("Vertex transformation", "x; y; z", Patterns::Anything(),
                      "New position of every mesh vertex as three "
                      "expressions of its position x, y, z separated by "
                      "';', applied after the mesh is built or "
                      "refined: an imperfection, a curved mid-surface (e.g. "
                      "an optic's sag), a change of frame. The result is "
                      "the stress-free reference configuration. Unit: "
                      "length (m in SI, mm in the IOL scenes).");
    prm.leave_subsection();
  }

  std::string resolve_path(const std::string &file,
                           const std::string &prm_directory)
  {
    if (file.empty() || std::filesystem::path(file).is_absolute() ||
        std::filesystem::exists(file))
      return file;
    const auto beside_prm = std::filesystem::path(prm_directory) / file;
    return std::filesystem::exists(beside_prm) ? beside_prm.string() : file;
  }

  void MeshParameters::parse_parameters(ParameterHandler  &prm,
                                        const std::string &prm_directory)
  {
    prm.enter_subsection("Mesh");
    source         = prm.get("Source");
    gmsh_file      = resolve_path(prm.get("Gmsh file"), prm_directory);
    gmsh_constants = parse_gmsh_constants(prm.get("Gmsh parameters"),
                                          "Mesh/Gmsh parameters");
    pattern        = parse_triangle_pattern(prm.get("Triangle pattern"));
    length_x       = prm.get_double("Length x");
    length_y       = prm.get_double("Length y");
    subdivisions_x = prm.get_integer("Subdivisions x");
    subdivisions_y = prm.get_integer("Subdivisions y");
    refinement_levels.clear();
    for (const int level : Utilities::string_to_int(
             Utilities::split_string_list(prm.get("Refinement levels"))))
      refinement_levels.push_back(level);
    const std::vector<double> normal = Utilities::string_to_double(
        Utilities::split_string_list(prm.get("Normal reference")));
    normal_reference = Tensor<1, 3>({normal[0], normal[1], normal[2]});
    const std::string transformation = prm.get("Vertex transformation");
    prm.leave_subsection();
    vertex_transformation.reset();
    if (Utilities::trim(transformation) != "x; y; z")
      vertex_transformation =
          base::parse_expressions<3>(transformation, 3, "x,y,z", false,
                                     "x, y, z", "Mesh/Vertex transformation");
    if (source == "gmsh" && gmsh_file.empty())
      throw std::invalid_argument(
          "Mesh/Gmsh file must be set when Mesh/Source = gmsh");
    if (source == "rectangle" && !(length_x > 0 && length_y > 0))
      throw std::invalid_argument("Mesh/Length x and Length y must be > 0");
  }

  void MeshParameters::build(Surface &surface, unsigned int level) const
  {
    const unsigned int factor = 1u << level;
    if (source == "rectangle")
      make_rectangle(surface, length_x, length_y, subdivisions_x * factor,
                     subdivisions_y * factor, pattern);
    else if (std::filesystem::path(gmsh_file).extension() == ".geo")
      read_gmsh(surface, gmsh_file, level, gmsh_constants);
    else
    {
      read_gmsh(surface, gmsh_file, 0, gmsh_constants);
      surface.refine_global(level);
    }
    if (vertex_transformation)
      GridTools::transform(
          [this](const Point<3> &p)
          {
            Point<3> moved;
            for (unsigned int d = 0; d < 3; ++d)
              moved[d] = vertex_transformation->value(p, d);
            return moved;
          },
          surface);
    check_cells(surface);
  }
} // namespace coshell::mesh
