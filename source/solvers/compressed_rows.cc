#include "compressed_rows.h"

namespace coshell::solvers
{
  void CompressedRows::copy(const dealii::SparseMatrix<double> &matrix,
                            bool                                lower_only)
  {
    const unsigned int n = matrix.m();
    starts.assign(n + 1, 0);
    indices.resize(matrix.n_nonzero_elements());
    values.resize(matrix.n_nonzero_elements());
    int k = 0;
    for (unsigned int row = 0; row < n; ++row)
    {
      starts[row] = k;
      // Insertion of each entry at its sorted place: only the leading
      // diagonal entry moves, the rest is stored ascending already.
      for (auto entry = matrix.begin(row); entry != matrix.end(row); ++entry)
      {
        // The pattern reserves room for every contact pair that may come
        // within reach during a step; most of those entries stay exactly
        // zero (70 % of a folded lens's), and factorized they would only
        // cost fill and flops. The diagonal is kept whatever its value.
        if (lower_only && entry->column() > row)
          break; // the rest of the row lies above the diagonal too
        if (entry->value() == 0.0 && entry->column() != row)
          continue;
        int place = k++;
        for (; place > starts[row] &&
               indices[place - 1] > static_cast<int>(entry->column());
             --place)
        {
          indices[place] = indices[place - 1];
          values[place]  = values[place - 1];
        }
        indices[place] = entry->column();
        values[place]  = entry->value();
      }
    }
    starts[n] = k;
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
