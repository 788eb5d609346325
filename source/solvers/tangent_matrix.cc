#include <coshell/solvers/tangent_matrix.h>

#include <stdexcept>

namespace coshell::solvers
{
  using namespace dealii;

  void TangentMatrix::reinit(const SparsityPattern &pattern)
  {
    trilinos_pattern_ = nullptr;
    trilinos_.reset();
    serial_.reinit(pattern);
    mirrors_.clear();
  }

  void TangentMatrix::reinit(const TrilinosWrappers::SparsityPattern &pattern)
  {
    trilinos_pattern_ = &pattern;
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
    const SparsityPattern &pattern = serial_.get_sparsity_pattern();
    if (mirrors_.empty())
      for (SparsityPattern::size_type row = 0; row < pattern.n_rows(); ++row)
        for (auto entry = pattern.begin(row); entry != pattern.end(row);
             ++entry)
          if (entry->column() < row)
          {
            const std::size_t mirror = pattern(entry->column(), row);
            if (mirror == SparsityPattern::invalid_entry)
              throw std::logic_error("TangentMatrix::mirror_lower(): the "
                                     "pattern is not symmetric");
            mirrors_.emplace_back(entry->global_index(), mirror);
          }
    using Entry = SparseMatrixIterators::Iterator<double, false>;
    for (const auto &[from, to] : mirrors_)
    {
      // A double, not the proxy: assigning one proxy to another would
      // copy the proxy and leave the matrix as it was.
      const double value           = Entry(&serial_, from)->value();
      Entry(&serial_, to)->value() = value;
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
} // namespace coshell::solvers
