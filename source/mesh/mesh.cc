#include <coshell/base/expressions.h>
#include <coshell/mesh/mesh.h>

#include <deal.II/base/utilities.h>
#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria_description.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <optional>
#include <sstream>
#include <stdexcept>

#include <unistd.h>

namespace coshell::mesh
{
  using namespace dealii;

  TrianglePattern parse_triangle_pattern(const std::string &name)
  {
    if (name == "same-diagonal")
      return TrianglePattern::same_diagonal;
    if (name == "alternating")
      return TrianglePattern::alternating;
    if (name == "crossed")
      return TrianglePattern::crossed;
    throw std::invalid_argument("unknown triangle pattern '" + name +
                                "' (same-diagonal|alternating|crossed)");
  }

  namespace
  {
    CellData<2> triangle(unsigned int a, unsigned int b, unsigned int c)
    {
      CellData<2> cell(3);
      cell.vertices = {a, b, c};
      return cell;
    }

    /// Splits the square with corners (lower-left, lower-right, upper-left,
    /// upper-right) = (v00, v10, v01, v11) into counter-clockwise triangles.
    void split_square(std::vector<CellData<2>> &cells,
                      unsigned int              v00,
                      unsigned int              v10,
                      unsigned int              v01,
                      unsigned int              v11,
                      bool                      rising_diagonal)
    {
      if (rising_diagonal)
      {
        cells.push_back(triangle(v00, v10, v11));
        cells.push_back(triangle(v00, v11, v01));
      }
      else
      {
        cells.push_back(triangle(v00, v10, v01));
        cells.push_back(triangle(v10, v11, v01));
      }
    }

    void set_rectangle_boundary_ids(Surface &surface,
                                    double   length_x,
                                    double   length_y)
    {
      const double tol = 1e-10 * std::max(length_x, length_y);
      for (const auto &cell : surface.active_cell_iterators())
        for (const auto &face : cell->face_iterators())
          if (face->at_boundary())
          {
            const Point<3> c = face->center();
            if (std::abs(c[0]) < tol)
              face->set_boundary_id(0);
            else if (std::abs(c[0] - length_x) < tol)
              face->set_boundary_id(1);
            else if (std::abs(c[1]) < tol)
              face->set_boundary_id(2);
            else
              face->set_boundary_id(3);
          }
    }
  } // namespace

  void make_rectangle(Surface        &surface,
                      double          length_x,
                      double          length_y,
                      unsigned int    n_x,
                      unsigned int    n_y,
                      TrianglePattern pattern)
  {
    if (n_x == 0 || n_y == 0 || !(length_x > 0) || !(length_y > 0))
      throw std::invalid_argument("rectangle needs positive lengths and "
                                  "subdivisions");
    std::vector<Point<3>> vertices;
    const auto            grid_vertex = [n_x](unsigned int i, unsigned int j)
    { return j * (n_x + 1) + i; };
    for (unsigned int j = 0; j <= n_y; ++j)
      for (unsigned int i = 0; i <= n_x; ++i)
        vertices.emplace_back(length_x * i / n_x, length_y * j / n_y, 0.0);

    std::vector<CellData<2>> cells;
    for (unsigned int j = 0; j < n_y; ++j)
      for (unsigned int i = 0; i < n_x; ++i)
      {
        const unsigned int v00 = grid_vertex(i, j), v10 = grid_vertex(i + 1, j),
                           v01 = grid_vertex(i, j + 1),
                           v11 = grid_vertex(i + 1, j + 1);
        if (pattern == TrianglePattern::crossed)
        {
          const unsigned int centre = vertices.size();
          vertices.push_back(Point<3>(length_x * (i + 0.5) / n_x,
                                      length_y * (j + 0.5) / n_y, 0.0));
          cells.push_back(triangle(v00, v10, centre));
          cells.push_back(triangle(v10, v11, centre));
          cells.push_back(triangle(v11, v01, centre));
          cells.push_back(triangle(v01, v00, centre));
        }
        else
          split_square(cells, v00, v10, v01, v11,
                       pattern == TrianglePattern::same_diagonal ||
                           (i + j) % 2 == 0);
      }
    surface.clear();
    surface.create_triangulation(vertices, cells, SubCellData());
    set_rectangle_boundary_ids(surface, length_x, length_y);
  }

  namespace
  {
    std::string mesh_geo_file(const std::string   &geo_file,
                              unsigned int         level,
                              const GmshConstants &constants)
    {
      static unsigned int geo_meshes_made = 0;
      const auto          output =
          std::filesystem::temp_directory_path() /
          ("coshell-" + std::to_string(::getpid()) + "-" +
           std::to_string(++geo_meshes_made) + "-" +
           std::filesystem::path(geo_file).stem().string() + ".msh");
      std::ostringstream command;
      command << "gmsh -2 -format msh2 -v 1 -setnumber refinement_level "
              << level;
      for (const auto &[name, value] : constants)
        command << " -setnumber " << name << ' ' << std::setprecision(17)
                << value;
      // gmsh's own messages go to a log beside the mesh: its first error
      // line (a .geo file's Error() explains a bad parameter) is shown.
      const std::string log = output.string() + ".log";
      command << " -o '" << output.string() << "' '" << geo_file << "' > '"
              << log << "' 2>&1";
      const bool meshed = std::system(command.str().c_str()) == 0 &&
                          std::filesystem::exists(output);
      std::string   error_line;
      std::ifstream gmsh_log(log);
      for (std::string line; !meshed && std::getline(gmsh_log, line);)
        if (line.rfind("Error", 0) == 0)
        {
          error_line = Utilities::trim(line);
          break;
        }
      std::filesystem::remove(log);
      if (!meshed)
      {
        // A .geo's Error() still lets gmsh write its mesh before it exits
        // non-zero: leave nothing of the failed run in the temp directory.
        std::error_code ignored;
        std::filesystem::remove(output, ignored);
        throw std::runtime_error("gmsh could not mesh '" + geo_file + "'" +
                                 (error_line.empty()
                                      ? std::string(" (is the gmsh executable "
                                                    "installed? command: " +
                                                    command.str() + ")")
                                      : ": " + error_line));
      }
      return output.string();
    }

    void read_msh_file(Surface &surface, const std::string &file)
    {
      std::ifstream input(file);
      if (!input)
        throw std::runtime_error("cannot open mesh file '" + file + "'");
      GridIn<2, 3> grid_in;
      grid_in.attach_triangulation(surface);
      try
      {
        grid_in.read_msh(input);
      }
      catch (const ExceptionBase &error)
      {
        std::ostringstream details;
        error.print_info(details);
        throw std::runtime_error("cannot read gmsh mesh '" + file +
                                 "': " + Utilities::trim(details.str()));
      }
    }
  } // namespace

  GmshConstants parse_gmsh_constants(const std::string &text,
                                     const std::string &where)
  {
    return base::parse_named_values(text, where);
  }

  void read_gmsh(Surface             &surface,
                 const std::string   &file,
                 unsigned int         level,
                 const GmshConstants &constants)
  {
    if (!std::filesystem::exists(file))
      throw std::runtime_error("mesh file '" + file + "' does not exist");
    surface.clear();
    if (std::filesystem::path(file).extension() == ".geo")
    {
      const std::string msh = mesh_geo_file(file, level, constants);
      try
      {
        read_msh_file(surface, msh);
      }
      catch (...)
      {
        std::filesystem::remove(msh);
        throw;
      }
      std::filesystem::remove(msh);
    }
    else if (!constants.empty())
      throw std::runtime_error("mesh file '" + file +
                               "' is not a .geo file; it takes no gmsh "
                               "parameters");
    else
      read_msh_file(surface, file);
  }

  void partition(Surface &surface, unsigned int n_parts)
  {
    if (surface.n_active_cells() < 2 * n_parts)
      throw std::invalid_argument(
          "the mesh has " + std::to_string(surface.n_active_cells()) +
          " triangles, too few for " + std::to_string(n_parts) +
          " MPI ranks (at least two per rank)");
    GridTools::partition_triangulation(n_parts, surface,
                                       SparsityTools::Partitioner::metis);
  }

  void check_cells(const Surface &surface)
  {
    if (surface.n_active_cells() == 0)
      throw std::runtime_error("the mesh has no cells");
    for (const auto &cell : surface.active_cell_iterators())
    {
      if (!cell->reference_cell().is_simplex())
        throw std::runtime_error("cell " + std::to_string(cell->index()) +
                                 " is not a triangle; CoShell meshes are "
                                 "made of triangles only");
      const Tensor<1, 3> a       = cell->vertex(1) - cell->vertex(0);
      const Tensor<1, 3> b       = cell->vertex(2) - cell->vertex(0);
      const double       longest = std::max(
                {a.norm(), b.norm(), (cell->vertex(2) - cell->vertex(1)).norm()});
      if (!(cross_product_3d(a, b).norm() > 1e-12 * longest * longest))
      {
        std::ostringstream message;
        message << "degenerate triangle: cell " << cell->index()
                << " with vertices (" << cell->vertex(0) << "), ("
                << cell->vertex(1) << "), (" << cell->vertex(2)
                << ") has (numerically) zero area";
        throw std::runtime_error(message.str());
      }
    }
  }
} // namespace coshell::mesh
