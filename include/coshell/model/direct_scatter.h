#pragma once

// Adding a contact pair's local matrix and vector into the global ones
// when no DoF is constrained, the case of free-flying scenes (the IOL
// injection). deal.II's AffineConstraints::distribute_local_to_global
// needs the block trimmed to the pattern first (ShellProblem::
// within_pattern(), a copy and a bisection per entry); here each row is
// bisected once per run of the block's sorted columns and walked, and
// couplings the pattern lacks are left out on the way. The sums are the
// same, entry by entry and in the same order of blocks, so the results
// are identical to the bit. The contact pair terms add faster this way;
// for the cells' 18 x 18 blocks, which the pattern always holds,
// deal.II's path is faster than this bisection (doc/performance.md). The
// cells have their own map instead (CellScatter, below).

#include <deal.II/base/types.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>

#include <vector>

namespace coshell::model
{
  class DirectScatter
  {
  public:
    /// Adds 'local' (if given a matrix) and 'local_vector' (if given a
    /// vector) at 'dofs', which must be distinct. Couplings that the matrix's
    /// pattern lacks are left out, as ShellProblem::within_pattern() leaves
    /// them. With 'lower_only', only the entries with column <= row
    /// (base::TangentMatrix::set_lower_only()).
    void add(const dealii::FullMatrix<double>                   &local,
             const dealii::Vector<double>                       &local_vector,
             const std::vector<dealii::types::global_dof_index> &dofs,
             dealii::SparseMatrix<double>                       *matrix,
             dealii::Vector<double>                             *vector,
             bool lower_only = false);

  private:
    void add_row(const dealii::FullMatrix<double>                   &local,
                 unsigned int                                        i,
                 const std::vector<dealii::types::global_dof_index> &dofs,
                 dealii::SparseMatrix<double>                       &matrix,
                 bool lower_only) const;

    /// The block's local indices sorted by global DoF (reused storage).
    std::vector<unsigned int> order_;
  };

  /// Adding the cells' 18 x 18 matrices into a deal.II matrix without
  /// constraints through a map of where each entry sits in the matrix's
  /// value array, found once per sparsity pattern. The same cells are
  /// added in every evaluation, so the row searches of deal.II's
  /// distribute_local_to_global are paid once instead of at every
  /// assembly (doc/performance.md). The sums are the same, in
  /// the same order, so results are identical to the bit. The map holds
  /// 324 indices a cell, and which 171 of them lie on or below the
  /// diagonal; a mesh whose map would pass 'largest_map_bytes'
  /// keeps deal.II's path: there the solve, not the scatter, dominates.
  class CellScatter
  {
  public:
    static constexpr std::size_t largest_map_bytes = std::size_t(64) << 20;

    /// Forgets the map: the pattern has changed. A matrix of another
    /// pattern object, or of another size, also starts a new map.
    void invalidate();
    /// Whether a mesh of 'n_cells' gets a map.
    static bool worth_a_map(unsigned int n_cells);
    /// Adds cell 'cell_index's 'local' matrix at 'dofs' (the cell's DoFs in
    /// the order of its local matrix); with 'lower_only' only the entries
    /// with column <= row. The first call after invalidate() maps the cell.
    void add(const dealii::FullMatrix<double>                   &local,
             unsigned int                                        cell_index,
             const std::vector<dealii::types::global_dof_index> &dofs,
             dealii::SparseMatrix<double>                       &matrix,
             bool lower_only = false);

  private:
    /// Per cell, the value-array index of each local entry (row-major);
    /// 'mapped_' tells which cells have theirs.
    std::vector<unsigned int> positions_;
    /// Per cell, the local entries (row-major index) with column <= row
    /// in the matrix: 171 of the 324, the diagonal's 18 and half the rest.
    std::vector<unsigned short>    lower_entries_;
    std::vector<bool>              mapped_;
    const dealii::SparsityPattern *pattern_   = nullptr;
    std::size_t                    n_entries_ = 0;
    void                           map_cell(unsigned int cell_index,
                                            const std::vector<dealii::types::global_dof_index> &dofs,
                                            const dealii::SparsityPattern                      &pattern);
  };
} // namespace coshell::model
