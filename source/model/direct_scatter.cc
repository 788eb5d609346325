#include <coshell/element/shell_element.h>
#include <coshell/model/direct_scatter.h>

#include <algorithm>
#include <numeric>

namespace coshell::model
{
  using namespace dealii;

  void DirectScatter::add(const FullMatrix<double> &local,
                          const Vector<double>     &local_vector,
                          const std::vector<types::global_dof_index> &dofs,
                          SparseMatrix<double>                       *matrix,
                          Vector<double>                             *vector,
                          bool lower_only)
  {
    if (vector)
      for (unsigned int i = 0; i < dofs.size(); ++i)
        (*vector)(dofs[i]) += local_vector(i);
    if (!matrix)
      return;
    order_.resize(dofs.size());
    std::iota(order_.begin(), order_.end(), 0u);
    std::sort(order_.begin(), order_.end(),
              [&](unsigned int a, unsigned int b)
              { return dofs[a] < dofs[b]; });
    for (unsigned int i = 0; i < dofs.size(); ++i)
      add_row(local, i, dofs, *matrix, lower_only);
  }

  namespace
  {
    /// The first place k >= 'from' of 'row' whose column is not below
    /// 'column', by bisection (the row's columns ascend after the
    /// diagonal).
    unsigned int lower_bound(const SparsityPattern  &pattern,
                             types::global_dof_index row,
                             unsigned int            from,
                             types::global_dof_index column)
    {
      unsigned int to = pattern.row_length(row);
      while (from < to)
      {
        const unsigned int middle = from + (to - from) / 2;
        if (pattern.column_number(row, middle) < column)
          from = middle + 1;
        else
          to = middle;
      }
      return from;
    }
  } // namespace

  void DirectScatter::add_row(const FullMatrix<double>                   &local,
                              unsigned int                                i,
                              const std::vector<types::global_dof_index> &dofs,
                              SparseMatrix<double> &matrix,
                              bool                  lower_only) const
  {
    const SparsityPattern        &pattern = matrix.get_sparsity_pattern();
    const types::global_dof_index row     = dofs[i];
    const unsigned int            length  = pattern.row_length(row);
    // A square deal.II pattern stores the diagonal first, then the rest
    // of the row in increasing column order.
    const std::size_t first  = pattern(row, row);
    const auto        add_at = [&](unsigned int k, double value)
    {
      SparseMatrixIterators::Iterator<double, false>(&matrix, first + k)
          ->value() += value;
    };
    add_at(0, local(i, i));
    // A block's DoFs come in runs (a vertex's six), and so do the row's
    // columns: after one bisection per run the walk finds the next
    // column at the next place.
    unsigned int k = 1;
    for (const unsigned int j : order_)
    {
      if (lower_only && dofs[j] > row)
        break; // the columns ascend: the rest lie above the diagonal
      if (j == i)
        continue;
      if (k >= length || pattern.column_number(row, k) != dofs[j])
        k = lower_bound(pattern, row, std::max(k, 1u), dofs[j]);
      if (k < length && pattern.column_number(row, k) == dofs[j])
        add_at(k++, local(i, j));
    }
  }
} // namespace coshell::model

namespace coshell::model
{
  namespace
  {
    constexpr unsigned int entries_per_cell =
        element::shell_dofs * element::shell_dofs;
    /// The entries with column <= row of a cell's distinct DoFs.
    constexpr unsigned int lower_entries_per_cell =
        (entries_per_cell + element::shell_dofs) / 2;
  } // namespace

  void CellScatter::invalidate()
  {
    positions_.clear();
    lower_entries_.clear();
    mapped_.clear();
    pattern_ = nullptr;
  }

  bool CellScatter::worth_a_map(const unsigned int n_cells)
  {
    return std::size_t(n_cells) *
               (entries_per_cell * sizeof(unsigned int) +
                lower_entries_per_cell * sizeof(unsigned short)) <=
           largest_map_bytes;
  }

  void CellScatter::add(const FullMatrix<double>                   &local,
                        const unsigned int                          cell_index,
                        const std::vector<types::global_dof_index> &dofs,
                        SparseMatrix<double>                       &matrix,
                        bool                                        lower_only)
  {
    const SparsityPattern &pattern = matrix.get_sparsity_pattern();
    if (&pattern != pattern_ || pattern.n_nonzero_elements() != n_entries_)
    {
      invalidate();
      pattern_   = &pattern;
      n_entries_ = pattern.n_nonzero_elements();
    }
    if (cell_index >= mapped_.size())
    {
      mapped_.resize(cell_index + 1, false);
      positions_.resize(std::size_t(cell_index + 1) * entries_per_cell);
      lower_entries_.resize(std::size_t(cell_index + 1) *
                            lower_entries_per_cell);
    }
    if (!mapped_[cell_index])
      map_cell(cell_index, dofs, pattern);
    const unsigned int *position =
        positions_.data() + std::size_t(cell_index) * entries_per_cell;
    // An iterator made from an index into the value array is that index,
    // nothing more: no row is looked up.
    if (lower_only)
    {
      // Each entry gets the same sum, in the same order of cells, as the
      // whole matrix's: the lower triangle is the same to the bit.
      const unsigned short *entry =
          lower_entries_.data() +
          std::size_t(cell_index) * lower_entries_per_cell;
      const double *values = &local(0, 0);
      for (unsigned int k = 0; k < lower_entries_per_cell; ++k, ++entry)
        SparseMatrixIterators::Iterator<double, false>(&matrix,
                                                       position[*entry])
            ->value() += values[*entry];
      return;
    }
    for (unsigned int i = 0; i < local.m(); ++i)
      for (unsigned int j = 0; j < local.n(); ++j, ++position)
        SparseMatrixIterators::Iterator<double, false>(&matrix, *position)
            ->value() += local(i, j);
  }

  void CellScatter::map_cell(const unsigned int cell_index,
                             const std::vector<types::global_dof_index> &dofs,
                             const SparsityPattern &pattern)
  {
    AssertThrow(dofs.size() == element::shell_dofs,
                ExcMessage("a cell block of another size than the shell's"));
    unsigned int *position =
        positions_.data() + std::size_t(cell_index) * entries_per_cell;
    unsigned short *lower = lower_entries_.data() +
                            std::size_t(cell_index) * lower_entries_per_cell;
    unsigned int n_lower = 0;
    for (unsigned int k = 0; k < entries_per_cell; ++k)
    {
      const auto        row    = dofs[k / element::shell_dofs];
      const auto        column = dofs[k % element::shell_dofs];
      const std::size_t index  = pattern(row, column);
      AssertThrow(index != SparsityPattern::invalid_entry,
                  ExcMessage("the sparsity pattern lacks a cell's coupling"));
      *position++ = static_cast<unsigned int>(index);
      if (column <= row && n_lower++ < lower_entries_per_cell)
        *lower++ = static_cast<unsigned short>(k);
    }
    AssertThrow(n_lower == lower_entries_per_cell,
                ExcMessage("a cell's DoFs are not distinct"));
    mapped_[cell_index] = true;
  }
} // namespace coshell::model
