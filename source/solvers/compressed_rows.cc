#include "compressed_rows.h"

#include <deal.II/lac/sparsity_pattern.h>

namespace coshell::solvers
{
  void CompressedRows::copy(const dealii::SparseMatrix<double> &matrix,
                            bool                                lower_only)
  {
    const dealii::SparsityPattern &pattern = matrix.get_sparsity_pattern();
    const unsigned int             n       = matrix.m();
    starts.resize(n + 1);
    indices.resize(matrix.n_nonzero_elements());
    values.resize(matrix.n_nonzero_elements());
    starts[0] = 0;
    if (n == 0)
      return;
    // deal.II keeps each row's values contiguous, in the order of its
    // pattern's columns: the diagonal first, then the others ascending
    // (a square matrix). Walking the raw rows costs a third of walking
    // the matrix's iterators, and this copy runs before every
    // factorization.
    const double *row_values = &matrix(0, 0); // row 0 starts with its diagonal
    int          *index      = indices.data();
    double       *value      = values.data();
    for (unsigned int row = 0; row < n; ++row)
    {
      starts[row]                 = static_cast<int>(index - indices.data());
      const unsigned int length   = pattern.row_length(row);
      const double       diagonal = row_values[0];
      // The pattern reserves room for every contact pair that may come
      // within reach during a step; most of those entries stay exactly
      // zero, and factorized they would only cost fill and flops. The diagonal is kept whatever its value.
      unsigned int entry = 1;
      for (; entry < length; ++entry)
      {
        const auto column = pattern.column_number(row, entry);
        if (column > row)
          break;
        if (row_values[entry] != 0.0)
        {
          *index++ = static_cast<int>(column);
          *value++ = row_values[entry];
        }
      }
      *index++ = static_cast<int>(row);
      *value++ = diagonal;
      if (!lower_only)
        for (; entry < length; ++entry)
          if (row_values[entry] != 0.0)
          {
            *index++ = static_cast<int>(pattern.column_number(row, entry));
            *value++ = row_values[entry];
          }
      row_values += length;
    }
    const auto k = index - indices.data();
    starts[n]    = static_cast<int>(k);
    indices.resize(k);
    values.resize(k);
  }

  bool CompressedRows::same_pattern(const CompressedRows &other) const
  {
    return starts == other.starts && indices == other.indices;
  }

  int CompressedRows::n_rows() const
  {
    return static_cast<int>(starts.size()) - 1;
  }
} // namespace coshell::solvers
