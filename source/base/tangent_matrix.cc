#include <coshell/base/tangent_matrix.h>

#include <stdexcept>

namespace coshell::base
{
  using namespace dealii;

  void TangentMatrix::reinit(const SparsityPattern &pattern)
  {
    trilinos_pattern_ = nullptr;
    trilinos_.reset();
    serial_.reinit(pattern);
    versioned_pattern_ = nullptr;
    lower_only_        = false;
    mirrors_.clear();
  }

  void TangentMatrix::reinit(const SparsityPattern &pattern,
                             std::uint64_t          version)
  {
    if (versioned_pattern_ == &pattern && pattern_version_ == version &&
        !distributed())
    {
      lower_only_ = false; // the mirrors of the same pattern stay valid
      return;
    }
    reinit(pattern);
    versioned_pattern_ = &pattern;
    pattern_version_   = version;
  }

  void TangentMatrix::reinit(const TrilinosWrappers::SparsityPattern &pattern)
  {
    trilinos_pattern_  = &pattern;
    versioned_pattern_ = nullptr;
    serial_.clear();
    trilinos_.reset();
  }

  bool TangentMatrix::distributed() const
  {
    return trilinos_pattern_ != nullptr;
  }

  void TangentMatrix::zero()
  {
    if (!distributed())
    {
      serial_ = 0;
      return;
    }
    if (!trilinos_)
    {
      trilinos_ = std::make_unique<TrilinosWrappers::SparseMatrix>();
      trilinos_->reinit(*trilinos_pattern_);
    }
    else
      *trilinos_ = 0;
  }

  SparseMatrix<double> &TangentMatrix::serial()
  {
    if (distributed())
      throw std::logic_error("TangentMatrix::serial() of a distributed "
                             "tangent");
    return serial_;
  }

  void TangentMatrix::set_lower_only(bool lower)
  {
    if (lower && distributed())
      throw std::logic_error("TangentMatrix: a distributed tangent is "
                             "assembled whole");
    lower_only_ = lower;
  }

  bool TangentMatrix::lower_only() const
  {
    return lower_only_;
  }

  void TangentMatrix::mirror_lower()
  {
    if (mirrors_.empty())
      find_mirrors();
    using Entry = SparseMatrixIterators::Iterator<double, false>;
    for (const auto &[from, to] : mirrors_)
    {
      // A double, not the proxy: assigning one proxy to another would
      // copy the proxy and leave the matrix as it was.
      const double value           = Entry(&serial_, from)->value();
      Entry(&serial_, to)->value() = value;
    }
  }

  /// One pass over the rows in order: the mirrors of the entries below the
  /// diagonal in rows 0, 1, 2, ... are, in each column c's own row c, the
  /// entries above its diagonal in ascending order. A cursor per row walks
  /// them, with no search.
  void TangentMatrix::find_mirrors()
  {
    const SparsityPattern &pattern = serial_.get_sparsity_pattern();
    const auto             n       = pattern.n_rows();
    if (n == 0)
      return;
    // deal.II stores each row's diagonal first, then the other columns
    // ascending: the entries above the diagonal end the row.
    std::vector<SparsityPattern::iterator> above(n, pattern.end(0));
    for (SparsityPattern::size_type row = 0; row < n; ++row)
    {
      above[row] = pattern.begin(row);
      while (above[row] != pattern.end(row) && above[row]->column() <= row)
        ++above[row];
    }
    mirrors_.reserve((pattern.n_nonzero_elements() - n) / 2);
    for (SparsityPattern::size_type row = 0; row < n; ++row)
      for (auto entry = pattern.begin(row); entry != pattern.end(row); ++entry)
      {
        const auto column = entry->column();
        if (column >= row)
          continue;
        if (above[column] == pattern.end(column) ||
            above[column]->column() != row)
          throw std::logic_error("TangentMatrix::mirror_lower(): the "
                                 "pattern is not symmetric");
        mirrors_.emplace_back(entry->global_index(),
                              above[column]->global_index());
        ++above[column];
      }
  }

  TrilinosWrappers::SparseMatrix &TangentMatrix::trilinos()
  {
    if (!trilinos_)
      throw std::logic_error("TangentMatrix::trilinos() before zero()");
    return *trilinos_;
  }

  TrilinosWrappers::SparseMatrix TangentMatrix::take_trilinos()
  {
    TrilinosWrappers::SparseMatrix taken(std::move(trilinos()));
    trilinos_.reset();
    return taken;
  }

  RowsOf::RowsOf(TrilinosWrappers::SparseMatrix &matrix, const IndexSet &rows)
      : matrix_(matrix), rows_(rows)
  {
  }

  RowsOf::size_type RowsOf::m() const
  {
    return matrix_.m();
  }

  RowsOf::size_type RowsOf::n() const
  {
    return matrix_.n();
  }

  unsigned int RowsOf::n_block_rows() const
  {
    return 1;
  }

  unsigned int RowsOf::n_block_cols() const
  {
    return 1;
  }

  void RowsOf::add(size_type        row,
                   size_type        n_columns,
                   const size_type *columns,
                   const double    *values,
                   bool             elide_zero_values,
                   bool             columns_are_sorted)
  {
    if (rows_.is_element(row))
      matrix_.add(row, n_columns, columns, values, elide_zero_values,
                  columns_are_sorted);
  }

  void RowsOf::add(size_type row, size_type column, double value)
  {
    if (rows_.is_element(row))
      matrix_.add(row, column, value);
  }
} // namespace coshell::base
