#pragma once

#include <coshell/element/shell_element.h>
#include <coshell/mesh/mesh.h>
#include <coshell/model/element_parameters.h>

#include <deal.II/base/index_set.h>
#include <deal.II/base/tensor.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>
#include <deal.II/lac/vector.h>

#include <array>
#include <string>
#include <vector>

namespace coshell::model
{
  using dealii::types::global_dof_index;
  using CellIterator = dealii::DoFHandler<2, 3>::active_cell_iterator;

  /// Per-vertex unknowns, in this order, in global axes.
  enum Component : unsigned int
  {
    ux,
    uy,
    uz,
    rx,
    ry,
    rz
  };
  constexpr unsigned int dofs_per_vertex = 6;

  /// "ux" -> Component::ux etc.; throws naming the accepted names.
  Component parse_component(const std::string &name);

  /// The six global DoF indices of one mesh vertex.
  using VertexDofs = std::array<global_dof_index, dofs_per_vertex>;

  /// The vertex's three entries of 'v' from component 'first' (ux or rx)
  /// on, as a vector.
  inline dealii::Tensor<1, 3> vertex_block(const dealii::Vector<double> &v,
                                           const VertexDofs             &dofs,
                                           unsigned int                  first)
  {
    dealii::Tensor<1, 3> x;
    for (unsigned int d = 0; d < 3; ++d)
      x[d] = v[dofs[first + d]];
    return x;
  }

  /// Discretization of a flat-facet shell: FESystem(FE_SimplexP(1), 6) on
  /// the surface, oriented cell normals, and the element kernels. Knows
  /// nothing of boundary conditions, loads or solvers.
  class ShellModel
  {
  public:
    ShellModel(const mesh::Surface        &surface,
               const ElementParameters    &element,
               const dealii::Tensor<1, 3> &normal_reference);

    const dealii::DoFHandler<2, 3> &dof_handler() const;
    const mesh::Surface            &surface() const;
    const ElementParameters        &element_parameters() const;
    global_dof_index                n_dofs() const;
    /// The DoFs of the cells this MPI rank owns (all of them on one rank):
    /// a contiguous range, the rows of distributed matrices this rank holds.
    const dealii::IndexSet &locally_owned_dofs() const;

    /// DoFs of vertex 'v' (a Triangulation vertex index); throws
    /// std::out_of_range for an index past the mesh's vertices (such as
    /// nearest_vertex()'s invalid index for a point at an infinite
    /// distance). Only vertices used by a cell have DoFs. Inline: the cell
    /// loops look up every vertex of every cell through it, in place of
    /// deal.II's slower vertex_dof_index(); the check is one compare.
    const VertexDofs &vertex_dofs(unsigned int v) const
    {
      if (v >= vertex_dofs_.size())
        throw_not_a_vertex(v); // out of line: the message's code inlined
                               // in every loop costs far more than the
                               // call
      return vertex_dofs_[v];
    }
    bool vertex_is_used(unsigned int v) const;

    /// Whether each used vertex has a thickness stretch unknown
    /// (Element/Thickness stretch). Its DoF holds lambda - 1, lambda =
    /// h / h0, so that zero is the reference as for every other DoF.
    bool has_thickness_stretch() const
    {
      return !thickness_dofs_.empty();
    }
    /// The DoFs of the six-component FESystem; the thickness stretches,
    /// when present, are numbered after them, n_fe_dofs() to n_dofs().
    global_dof_index n_fe_dofs() const;
    /// The thickness-stretch DoF of used vertex 'v' (only with
    /// has_thickness_stretch()).
    global_dof_index thickness_dof(unsigned int v) const
    {
      return thickness_dofs_[v];
    }
    /// lambda = h / h0 of used vertex 'v' in the configuration 'values'
    /// (only with has_thickness_stretch()).
    double thickness_stretch(unsigned int                  v,
                             const dealii::Vector<double> &values) const
    {
      return 1 + values[thickness_dofs_[v]];
    }
    /// The thickness of 'cell' in mm in the configuration 'values': h0
    /// times the mean stretch of its vertices (h0 without the stretch).
    double current_thickness(const CellIterator           &cell,
                             const dealii::Vector<double> &values) const;
    /// The first n_fe_dofs() entries of 'v': the part deal.II's DataOut
    /// and FEValues know (v itself when there is no thickness stretch).
    dealii::Vector<double> fe_part(const dealii::Vector<double> &v) const;
    /// A vector in the DoF layout rearranged by mesh vertex (6 entries per
    /// Triangulation vertex, component fastest, 0 at unused vertices; with
    /// the thickness stretch, one more block of 1 entry per vertex), and
    /// back: a layout that does not depend on the DoF numbering, which
    /// differs between serial and MPI runs. Checkpoints store it, so a run
    /// restarts on any number of ranks. Empty vectors stay empty;
    /// from_vertex_order() throws if the size does not fit the mesh.
    dealii::Vector<double>
    to_vertex_order(const dealii::Vector<double> &dofs) const;
    dealii::Vector<double>
    from_vertex_order(const dealii::Vector<double> &by_vertex) const;
    /// Vertex index closest to a point (among used vertices).
    unsigned int nearest_vertex(const dealii::Point<3> &point) const;

    /// The material of a cell: E and nu, and the thickness and density
    /// of its region and position (Material/Thickness and Density).
    const element::ShellMaterial &material(const CellIterator &cell) const;
    /// The element options of a cell: those of the prm, with the ANDES
    /// higher-order scale of that triangle.
    const element::ShellElementOptions &
    element_options(const CellIterator &cell) const;
    /// Area-weighted mean thickness of the cells around used vertex 'v'.
    double vertex_thickness(unsigned int v) const;
    /// Smallest and largest cell thickness.
    std::pair<double, double> thickness_range() const;
    /// The shell's mass, the sum over its cells of density x thickness x
    /// area (mass units of the scene: tonne in mm-N-s scenes); 0 without
    /// Material/Density. Every rank holds the whole mesh, so every rank
    /// gets the whole sum.
    double mass() const;

    element::SpatialTriangle triangle(const CellIterator &cell) const;
    /// Unit normal of the cell, oriented consistently over the surface.
    dealii::Tensor<1, 3> unit_normal(const CellIterator &cell) const;
    /// +1 if that normal is (x1-x0)x(x2-x0), -1 if it is the opposite.
    int normal_sign(const CellIterator &cell) const;
    /// Flips bending moments of cells whose normal is opposite to their
    /// element frame's e3, so moments are measured along the oriented
    /// normal everywhere.
    void orient_moments(const CellIterator       &cell,
                        element::ShellResultants &resultants) const;

    /// Sparsity of the stiffness with the given constraints, plus the
    /// translations of each pair of 'coupled' vertices (self contact).
    void make_sparsity(
        const dealii::AffineConstraints<double>        &constraints,
        dealii::SparsityPattern                        &pattern,
        const std::vector<std::array<unsigned int, 2>> &coupled = {}) const;
    /// Assembles the linear stiffness (multithreaded with WorkStream). On
    /// several ranks each assembles its cells and the ranks sum the whole
    /// matrix, which every rank then holds.
    void
    assemble_stiffness(const dealii::AffineConstraints<double> &constraints,
                       dealii::SparseMatrix<double>            &matrix) const;

    /// On several ranks: the pattern of the rows 'owned_rows' of this rank,
    /// which may also write to the rows of its cells that other ranks own,
    /// plus the translations of each pair of 'coupled' vertices in the rows
    /// it owns.
    void make_distributed_sparsity(
        const dealii::AffineConstraints<double>        &constraints,
        const dealii::IndexSet                         &owned_rows,
        dealii::TrilinosWrappers::SparsityPattern      &pattern,
        const std::vector<std::array<unsigned int, 2>> &coupled = {}) const;
    /// Assembles this rank's cells into a matrix on that pattern; entries
    /// of rows owned elsewhere travel to their rank once, in compress().
    void
    assemble_stiffness(const dealii::AffineConstraints<double> &constraints,
                       dealii::TrilinosWrappers::SparseMatrix  &matrix) const;

    /// The 18 element DoF values of a cell, in kernel order.
    element::ShellDisplacements
    cell_values(const CellIterator           &cell,
                const dealii::Vector<double> &u) const;

    /// Membrane forces and bending moments of every active cell.
    std::vector<element::ShellResultants>
    resultants(const dealii::Vector<double> &solution) const;

  private:
    template<typename Matrix>
    void assemble_owned_cells(const dealii::AffineConstraints<double> &,
                              Matrix &matrix) const;

    const mesh::Surface                      &surface_;
    ElementParameters                         element_;
    dealii::FESystem<2, 3>                    fe_;
    dealii::DoFHandler<2, 3>                  dof_handler_;
    std::vector<VertexDofs>                   vertex_dofs_;
    std::vector<global_dof_index>             thickness_dofs_;
    dealii::IndexSet                          locally_owned_dofs_;
    std::vector<int>                          normal_sign_;
    std::vector<element::ShellMaterial>       cell_materials_;
    std::vector<element::ShellElementOptions> cell_options_;
    std::vector<double>                       vertex_thickness_;

    void number_vertex_dofs();
    /// Entries per vertex beyond the six in the vertex order: 1 with the
    /// thickness stretch, else 0.
    unsigned int thickness_fields() const
    {
      return has_thickness_stretch() ? 1 : 0;
    }
    /// One DoF per used vertex after the FESystem's, with
    /// Element/Thickness stretch; refused on several ranks.
    void number_thickness_dofs();
    /// Adds each cell's thickness DoFs to its own and to each other.
    void
    add_thickness_sparsity(const dealii::AffineConstraints<double> &constraints,
                           dealii::DynamicSparsityPattern          &dsp) const;
    /// Throws std::out_of_range naming 'v' (vertex_dofs()).
    [[noreturn]] void throw_not_a_vertex(unsigned int v) const;
    /// cell_options_, with each triangle's ANDES drilling scales.
    void assign_cell_options();
    /// On several ranks: numbers DoFs part by part (the mesh's subdomain
    /// ids), so each rank owns a contiguous range.
    void number_dofs_by_rank();
    /// Evaluates Material/Thickness and Density per cell, checks them
    /// (naming the cell) and keeps their area-weighted means in element_.
    void assign_cell_materials();
    /// Material/'name' = 'text' at every cell's reference centroid, or
    /// 'uniform' everywhere when 'text' is empty.
    std::vector<double> cell_values_of(const std::string &text,
                                       const std::string &name,
                                       double             uniform) const;
  };
} // namespace coshell::model
