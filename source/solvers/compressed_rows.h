#pragma once

#include <deal.II/lac/sparse_matrix.h>

#include <vector>

namespace coshell::solvers
{
  /// A copy of a deal.II SparseMatrix in plain compressed-row arrays, the
  /// form SuiteSparse reads (as compressed columns of the transpose),
  /// without the off-diagonal entries that are exactly zero: the solvers
  /// analyse again when that pattern changes.
  /// Column indices ascend within each row: deal.II stores the diagonal
  /// first, UMFPACK rejects unsorted columns.
  struct CompressedRows
  {
    std::vector<int>    starts, indices;
    std::vector<double> values;

    /// Copies the whole matrix, or with 'lower_only' only the entries
    /// with column <= row: all that CHOLMOD reads of a symmetric one.
    void copy(const dealii::SparseMatrix<double> &matrix,
              bool                                lower_only = false);
    bool same_pattern(const CompressedRows &other) const;
    int  n_rows() const;
  };
} // namespace coshell::solvers
