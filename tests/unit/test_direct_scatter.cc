// DirectScatter and CellScatter against deal.II's
// AffineConstraints::distribute_local_to_global with no constraints: blocks
// with unsorted DoFs, some of whose couplings the pattern lacks (contact
// blocks), and repeated cell blocks give the same matrix and vector to the
// bit. Asked for the entries with column <= row only, both give the same
// lower triangle to the bit and leave the rest zero; mirrored, it is the
// whole matrix of symmetric blocks.

#include <coshell/base/tangent_matrix.h>
#include <coshell/element/shell_element.h>
#include <coshell/model/direct_scatter.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparsity_pattern.h>

#include <cmath>

#include <gtest/gtest.h>

using namespace dealii;

namespace
{
  using Dofs = std::vector<types::global_dof_index>;

  /// Entries of irrational size, so that summation order would show.
  double entry(unsigned int block, unsigned int i, unsigned int j)
  {
    return std::sin(1.0 + block + 0.37 * i + 1.71 * j) * std::sqrt(2.0 + i);
  }

  /// 'n_cells' "cells" of 18 DoFs each among n, overlapping, in no sorted
  /// order.
  std::vector<Dofs> overlapping_cells(unsigned int n_cells, unsigned int n)
  {
    std::vector<Dofs> cells(n_cells, Dofs(coshell::element::shell_dofs));
    for (unsigned int c = 0; c < n_cells; ++c)
      for (unsigned int i = 0; i < coshell::element::shell_dofs; ++i)
        cells[c][i] = (7 * i + 11 * c) % n;
    return cells;
  }
} // namespace

TEST(DirectScatter, SameSumsAsDealIIAndLeavesOutWhatThePatternLacks)
{
  const unsigned int      n = 10;
  const std::vector<Dofs> blocks{{7, 2, 5, 0}, {3, 9, 2}, {5, 0, 8, 1, 7}};
  // The pattern holds the couplings of the first two blocks only: the
  // third couples 8 and 1 with the rest beyond it.
  DynamicSparsityPattern dsp(n, n);
  for (unsigned int i = 0; i < n; ++i)
    dsp.add(i, i);
  for (unsigned int b = 0; b < 2; ++b)
    for (const auto i : blocks[b])
      for (const auto j : blocks[b])
        dsp.add(i, j);
  SparsityPattern pattern;
  pattern.copy_from(dsp);
  SparseMatrix<double>      direct(pattern), reference(pattern);
  Vector<double>            direct_vector(n), reference_vector(n);
  AffineConstraints<double> none;
  none.close();
  coshell::model::DirectScatter scatter;
  for (unsigned int b = 0; b < blocks.size(); ++b)
  {
    const Dofs        &dofs = blocks[b];
    FullMatrix<double> local(dofs.size()), trimmed(dofs.size());
    Vector<double>     local_vector(dofs.size());
    for (unsigned int i = 0; i < dofs.size(); ++i)
    {
      local_vector(i) = entry(b, i, 99);
      for (unsigned int j = 0; j < dofs.size(); ++j)
      {
        local(i, j) = entry(b, i, j);
        if (pattern(dofs[i], dofs[j]) != SparsityPattern::invalid_entry)
          trimmed(i, j) = local(i, j);
      }
    }
    scatter.add(local, local_vector, dofs, &direct, &direct_vector);
    none.distribute_local_to_global(trimmed, local_vector, dofs, reference,
                                    reference_vector);
  }
  for (unsigned int i = 0; i < n; ++i)
  {
    EXPECT_EQ(direct_vector(i), reference_vector(i)) << "row " << i;
    for (auto e = reference.begin(i); e != reference.end(i); ++e)
      EXPECT_EQ(direct.el(i, e->column()), e->value())
          << "entry (" << i << ", " << e->column() << ")";
  }
  // The third block's diagonal of DoF 8 had room in the pattern.
  EXPECT_EQ(direct.el(8, 8), entry(2, 2, 2));
  // A vector alone.
  Vector<double> only(n), values(3);
  values = 1.5;
  scatter.add(FullMatrix<double>(), values, {4, 6, 1}, nullptr, &only);
  EXPECT_EQ(only(6), 1.5);
  EXPECT_EQ(only.l1_norm(), 4.5);
}

TEST(CellScatter, SameSumsAsDealIIAcrossEvaluationsAndPatterns)
{
  const unsigned int      n     = 40;
  const unsigned int      n_dof = coshell::element::shell_dofs;
  const std::vector<Dofs> cells = overlapping_cells(3, n);
  const auto make_pattern       = [&](SparsityPattern &pattern, bool extra)
  {
    DynamicSparsityPattern dsp(n, n);
    for (const auto &dofs : cells)
      for (const auto i : dofs)
        for (const auto j : dofs)
          dsp.add(i, j);
    if (extra) // a contact coupling that shifts the rows' entries
      dsp.add(0, 39), dsp.add(39, 0);
    pattern.copy_from(dsp);
  };
  AffineConstraints<double> none;
  none.close();
  coshell::model::CellScatter scatter;
  for (const bool extra : {false, true})
  {
    SparsityPattern pattern;
    make_pattern(pattern, extra);
    SparseMatrix<double> direct(pattern), reference(pattern);
    // Two evaluations: the second uses the map the first made.
    for (unsigned int evaluation = 0; evaluation < 2; ++evaluation)
    {
      direct    = 0;
      reference = 0;
      for (unsigned int c = 0; c < cells.size(); ++c)
      {
        FullMatrix<double> local(n_dof);
        for (unsigned int i = 0; i < n_dof; ++i)
          for (unsigned int j = 0; j < n_dof; ++j)
            local(i, j) = entry(c + 3 * evaluation, i, j);
        scatter.add(local, c, cells[c], direct);
        none.distribute_local_to_global(local, cells[c], reference);
      }
      for (unsigned int i = 0; i < n; ++i)
        for (auto e = reference.begin(i); e != reference.end(i); ++e)
          ASSERT_EQ(direct.el(i, e->column()), e->value())
              << "entry (" << i << ", " << e->column() << "), pattern " << extra
              << ", evaluation " << evaluation;
    }
  }
}

TEST(LowerTriangleScatter, SameLowerTriangleToTheBitAndMirroredTheWhole)
{
  const unsigned int      n     = 40;
  const unsigned int      n_dof = coshell::element::shell_dofs;
  const std::vector<Dofs> cells = overlapping_cells(2, n);
  const Dofs              pair{33, 2, 17, 8};
  DynamicSparsityPattern  dsp(n, n);
  for (const auto &dofs : {cells[0], cells[1], pair})
    for (const auto i : dofs)
      for (const auto j : dofs)
        dsp.add(i, j);
  SparsityPattern pattern;
  pattern.copy_from(dsp);
  coshell::base::TangentMatrix whole, lower;
  whole.reinit(pattern);
  lower.reinit(pattern);
  lower.set_lower_only(true);
  coshell::model::CellScatter   cell_scatter, lower_cell_scatter;
  coshell::model::DirectScatter scatter;
  // Two evaluations: the second uses the maps the first made.
  for (unsigned int evaluation = 0; evaluation < 2; ++evaluation)
  {
    whole.zero();
    lower.zero();
    for (unsigned int c = 0; c < cells.size(); ++c)
    {
      FullMatrix<double> local(n_dof);
      for (unsigned int i = 0; i < n_dof; ++i)
        for (unsigned int j = 0; j <= i; ++j)
          local(i, j) = local(j, i) = entry(c + 2 * evaluation, i, j);
      cell_scatter.add(local, c, cells[c], whole.serial());
      lower_cell_scatter.add(local, c, cells[c], lower.serial(), true);
    }
    FullMatrix<double> block(pair.size());
    for (unsigned int i = 0; i < pair.size(); ++i)
      for (unsigned int j = 0; j <= i; ++j)
        block(i, j) = block(j, i) = entry(7 + evaluation, i, j);
    scatter.add(block, Vector<double>(), pair, &whole.serial(), nullptr);
    scatter.add(block, Vector<double>(), pair, &lower.serial(), nullptr, true);
    for (unsigned int i = 0; i < n; ++i)
      for (auto e = pattern.begin(i); e != pattern.end(i); ++e)
        ASSERT_EQ(lower.serial().el(i, e->column()),
                  e->column() <= i ? whole.serial().el(i, e->column()) : 0.0)
            << "entry (" << i << ", " << e->column() << ")";
    lower.mirror_lower();
    for (unsigned int i = 0; i < n; ++i)
      for (auto e = pattern.begin(i); e != pattern.end(i); ++e)
        ASSERT_EQ(lower.serial().el(i, e->column()),
                  whole.serial().el(i, e->column()))
            << "entry (" << i << ", " << e->column() << "), mirrored";
  }
  EXPECT_NE(whole.serial().el(2, 33), 0.0); // the pair's coupling came
}
