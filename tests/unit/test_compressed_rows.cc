// CompressedRows, the copy of a deal.II matrix that CHOLMOD and UMFPACK
// factorize: checked entry by entry against the matrix's own iterators
// (every entry but the exact zeros off the diagonal, columns ascending).
#include "../../source/solvers/compressed_rows.h"

#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparsity_pattern.h>

#include <gtest/gtest.h>

#include <map>
#include <utility>

namespace
{
  using namespace dealii;
  using coshell::solvers::CompressedRows;

  /// A symmetric pattern with a band, far couplings and rows holding only
  /// their diagonal; some entries of the pattern stay exactly zero, as a
  /// contact pair's reserved room does, and one diagonal is zero too.
  struct Matrix
  {
    SparsityPattern      pattern;
    SparseMatrix<double> matrix;

    Matrix()
    {
      const unsigned int     n = 23;
      DynamicSparsityPattern dsp(n, n);
      for (unsigned int i = 0; i < n; ++i)
        for (unsigned int j : {i, (i + 1) % n, (i * 7 + 3) % n})
          if (i % 5 != 4 || j == i)
          {
            dsp.add(i, j);
            dsp.add(j, i);
          }
      pattern.copy_from(dsp);
      matrix.reinit(pattern);
      for (unsigned int i = 0; i < n; ++i)
        for (auto entry = matrix.begin(i); entry != matrix.end(i); ++entry)
        {
          const unsigned int j = entry->column();
          // Exact zeros at every third coupling, and on diagonal 6.
          if ((i + j) % 3 != 0 && i != 6)
            entry->value() = 1.0 + i + 0.01 * j;
        }
    }

    /// (row, column) -> value of the entries a copy must keep.
    std::map<std::pair<int, int>, double> kept(bool lower_only) const
    {
      std::map<std::pair<int, int>, double> entries;
      for (unsigned int i = 0; i < matrix.m(); ++i)
        for (auto entry = matrix.begin(i); entry != matrix.end(i); ++entry)
        {
          const unsigned int j = entry->column();
          if ((lower_only && j > i) || (entry->value() == 0.0 && j != i))
            continue;
          entries[{int(i), int(j)}] = entry->value();
        }
      return entries;
    }
  };

  void expect_copy(const Matrix &m, bool lower_only)
  {
    CompressedRows rows;
    rows.copy(m.matrix, lower_only);
    const auto expected = m.kept(lower_only);
    ASSERT_EQ(rows.n_rows(), static_cast<int>(m.matrix.m()));
    ASSERT_EQ(rows.indices.size(), expected.size());
    auto next = expected.begin();
    for (int row = 0; row < rows.n_rows(); ++row)
      for (int k = rows.starts[row]; k < rows.starts[row + 1]; ++k, ++next)
      {
        // The map's order is row by row, columns ascending.
        EXPECT_EQ(next->first, std::make_pair(row, rows.indices[k]));
        EXPECT_EQ(next->second, rows.values[k]);
      }
  }

  TEST(CompressedRows, WholeMatrixWithoutItsZerosColumnsAscending)
  {
    expect_copy(Matrix(), false);
  }

  TEST(CompressedRows, LowerTriangleForCholmod)
  {
    expect_copy(Matrix(), true);
  }

  TEST(CompressedRows, PatternChangesWhenAnOffDiagonalEntryBecomesZero)
  {
    Matrix         m;
    CompressedRows before, after;
    before.copy(m.matrix, true);
    m.matrix *= 2.0;
    after.copy(m.matrix, true);
    EXPECT_TRUE(before.same_pattern(after)); // values alone changed
    m.matrix.set(2, 2, 0.0);
    after.copy(m.matrix, true);
    EXPECT_TRUE(before.same_pattern(after)); // a diagonal stays
    ASSERT_NE(m.matrix.el(3, 2), 0.0);
    m.matrix.set(3, 2, 0.0);
    after.copy(m.matrix, true);
    EXPECT_FALSE(before.same_pattern(after));
  }
} // namespace
