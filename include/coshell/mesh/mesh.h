#pragma once

#include <deal.II/base/function_parser.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/tensor.h>
#include <deal.II/grid/tria.h>

#include <memory>
#include <string>
#include <vector>

namespace coshell::mesh
{
  using Surface = dealii::Triangulation<2, 3>;

  /// How a generated rectangle splits each square into triangles.
  enum class TrianglePattern
  {
    same_diagonal, ///< every square split along the same diagonal
    alternating,   ///< diagonals alternate like a chessboard
    crossed        ///< four triangles per square around its centre
  };

  TrianglePattern parse_triangle_pattern(const std::string &name);

  /// Builds a [0,Lx]x[0,Ly] plate in the z=0 plane with nx x ny squares.
  /// Boundary ids: 0 at x=0, 1 at x=Lx, 2 at y=0, 3 at y=Ly.
  void make_rectangle(Surface        &surface,
                      double          length_x,
                      double          length_y,
                      unsigned int    n_x,
                      unsigned int    n_y,
                      TrianglePattern pattern);

  /// Reads a gmsh mesh. A ".msh" file is read as is; a ".geo" file is
  /// meshed by the gmsh executable first, with the gmsh constant
  /// 'refinement_level' set to 'level' (a .geo written for refinement
  /// studies declares it with DefineConstant and scales its element sizes
  /// by 2^-refinement_level). Physical surfaces become material ids,
  /// physical curves boundary ids. Throws std::runtime_error naming the
  /// file on any failure.
  /// gmsh constants given on the command line (-setnumber name value).
  using GmshConstants = std::vector<std::pair<std::string, double>>;

  /// Parses "name = value, name = value"; names are identifiers, values
  /// numbers or expressions of the scene's Constants (so that a mesh's
  /// design value can be the one the prm states once). Throws
  /// std::invalid_argument "<where>: ..." naming the bad entry.
  GmshConstants parse_gmsh_constants(const std::string &text,
                                     const std::string &where);

  /// 'constants' are set as well when a .geo file is meshed (and must be
  /// empty for a .msh file).
  void read_gmsh(Surface             &surface,
                 const std::string   &file,
                 unsigned int         level,
                 const GmshConstants &constants = {});

  /// A relative file name is looked up as given, then beside the prm file.
  std::string resolve_path(const std::string &file,
                           const std::string &prm_directory);

  /// Checks that every cell is a triangle with a non-degenerate area;
  /// throws std::runtime_error naming the first bad cell and its vertices.
  void check_cells(const Surface &surface);

  /// Splits the cells into 'n_parts' parts with METIS (cell subdomain ids
  /// 0 .. n_parts-1), one per MPI rank. Every rank holds the whole mesh and
  /// computes the same partition, like parallel::shared::Triangulation.
  void partition(Surface &surface, unsigned int n_parts);

  /// Mesh source and refinement, from the prm subsection "Mesh".
  struct MeshParameters
  {
    std::string               source = "rectangle";
    std::string               gmsh_file;
    GmshConstants             gmsh_constants;
    TrianglePattern           pattern  = TrianglePattern::crossed;
    double                    length_x = 1.0, length_y = 1.0;
    unsigned int              subdivisions_x = 4, subdivisions_y = 4;
    std::vector<unsigned int> refinement_levels{0};
    dealii::Tensor<1, 3>      normal_reference;
    /// Maps every vertex after the mesh is built; null: identity.
    std::shared_ptr<dealii::FunctionParser<3>> vertex_transformation;

    static void declare_parameters(dealii::ParameterHandler &prm);
    void        parse_parameters(dealii::ParameterHandler &prm,
                                 const std::string        &prm_directory);

    /// Builds the mesh of one refinement level: a generated rectangle gets
    /// 2^level times the subdivisions, a .geo file is re-meshed by gmsh
    /// with refinement_level = level, a .msh file is refined globally.
    void build(Surface &surface, unsigned int level) const;
  };

  /// Gives every active cell an orientation flag so that the normals
  /// n = +-(x1-x0)x(x2-x0) agree across shared edges, with each connected
  /// patch flipped so that its area-weighted normal points along
  /// 'reference' (when reference is non-zero). deal.II does not orient
  /// triangles consistently on surfaces, so this is done here.
  /// Result: +1 or -1 per active cell index.
  std::vector<int> orient_normals(const Surface              &surface,
                                  const dealii::Tensor<1, 3> &reference);
} // namespace coshell::mesh
