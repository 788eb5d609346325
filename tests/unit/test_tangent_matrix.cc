// The distributed tangent's pieces on one rank: RowsOf, through
// which terms that every rank computes alike reach a distributed matrix once,
// passes the rows it is given (constraints resolved as for a deal.II matrix,
// constrained diagonals included) and drops the others;
// TangentMatrix builds a fresh matrix on its pattern once the
// solver has taken the last one.
#include <coshell/base/parallel_environment.h>
#include <coshell/base/tangent_matrix.h>

#include <deal.II/lac/affine_constraints.templates.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <gtest/gtest.h>

namespace
{
  using namespace dealii;
  using coshell::base::RowsOf;
  using coshell::base::TangentMatrix;

  constexpr unsigned int n = 5;

  /// x1 = 0.5 x0 + 0.25 x3 (a slave tied to two masters) and x4 = 0.
  AffineConstraints<double> two_constraints()
  {
    AffineConstraints<double> constraints;
    constraints.add_line(1);
    constraints.add_entry(1, 0, 0.5);
    constraints.add_entry(1, 3, 0.25);
    constraints.add_line(4);
    constraints.close();
    return constraints;
  }

  /// A non-symmetric 4 x 4 block on DoFs {3, 1, 4, 0}.
  FullMatrix<double> block()
  {
    FullMatrix<double> local(4, 4);
    for (unsigned int i = 0; i < 4; ++i)
      for (unsigned int j = 0; j < 4; ++j)
        local(i, j) = (i == j ? 10.0 : 0.0) + 1.0 + i + 3.0 * j;
    return local;
  }

  DynamicSparsityPattern full_pattern()
  {
    DynamicSparsityPattern pattern(n, n);
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = 0; j < n; ++j)
        pattern.add(i, j);
    return pattern;
  }
} // namespace

TEST(RowsOf, PassesTheGivenRowsAsADealIIMatrixGetsThemAndDropsTheOthers)
{
  coshell::base::ensure_mpi_initialized();
  const auto                                 constraints = two_constraints();
  const std::vector<types::global_dof_index> dofs        = {3, 1, 4, 0};
  SparsityPattern                            serial_pattern;
  serial_pattern.copy_from(full_pattern());
  SparseMatrix<double> reference(serial_pattern);
  constraints.distribute_local_to_global(block(), dofs, reference);

  IndexSet rows(n);
  for (const types::global_dof_index row : {0, 1, 4})
    rows.add_index(row); // a master, the slave and the fixed DoF
  TrilinosWrappers::SparseMatrix matrix;
  matrix.reinit(complete_index_set(n), complete_index_set(n), full_pattern(),
                MPI_COMM_SELF);
  coshell::base::RowsOf owned(matrix, rows);
  constraints.distribute_local_to_global(block(), dofs, owned);
  matrix.compress(VectorOperation::add);

  for (unsigned int i = 0; i < n; ++i)
    for (unsigned int j = 0; j < n; ++j)
      EXPECT_DOUBLE_EQ(matrix.el(i, j),
                       rows.is_element(i) ? reference.el(i, j) : 0.0)
          << "entry (" << i << ", " << j << ")";
  EXPECT_NE(reference.el(4, 4), 0.0); // the fixed DoF's diagonal came through
  EXPECT_NE(reference.el(3, 0), 0.0); // a dropped row was not empty
}

TEST(TangentMatrix, BuildsAFreshMatrixOnItsPatternOnceTheLastIsTaken)
{
  coshell::base::ensure_mpi_initialized();
  TrilinosWrappers::SparsityPattern pattern(complete_index_set(n),
                                            MPI_COMM_SELF);
  pattern.add(2, 3);
  for (unsigned int i = 0; i < n; ++i)
    pattern.add(i, i);
  pattern.compress();
  coshell::base::TangentMatrix tangent;
  tangent.reinit(pattern);
  ASSERT_TRUE(tangent.distributed());
  tangent.zero();
  tangent.trilinos().add(2, 3, 7.0);
  tangent.trilinos().compress(VectorOperation::add);
  const auto taken = tangent.take_trilinos();
  EXPECT_EQ(taken.el(2, 3), 7.0);
  EXPECT_THROW(tangent.trilinos(), std::logic_error);
  tangent.zero();
  EXPECT_EQ(tangent.trilinos().n_nonzero_elements(), n + 1);
  EXPECT_EQ(tangent.trilinos().el(2, 3), 0.0);
  EXPECT_THROW(tangent.serial(), std::logic_error);
}

// A Newton keeps its tangent from one solve to the next: on the same pattern
// at the same version its storage stays (what it holds is the last
// assembly's, which the next zero() clears); a new version, or another
// pattern, makes it anew on that pattern.
TEST(TangentMatrix, KeepsItsStorageWhileThePatternVersionStays)
{
  SparsityPattern first, second;
  first.copy_from(full_pattern());
  DynamicSparsityPattern diagonal(n, n);
  for (unsigned int i = 0; i < n; ++i)
    diagonal.add(i, i);
  second.copy_from(diagonal);

  coshell::base::TangentMatrix tangent;
  tangent.reinit(first, 7);
  tangent.serial().set(2, 3, 1.5);
  const double *storage = &tangent.serial()(0, 0);
  tangent.set_lower_only(true);

  tangent.reinit(first, 7);
  EXPECT_EQ(&tangent.serial()(0, 0), storage);
  EXPECT_EQ(tangent.serial()(2, 3), 1.5);
  EXPECT_FALSE(tangent.lower_only());
  tangent.zero();
  EXPECT_EQ(tangent.serial()(2, 3), 0.0);

  tangent.serial().set(2, 3, 1.5);
  tangent.reinit(first, 8); // the same object made again: a new version
  EXPECT_EQ(tangent.serial()(2, 3), 0.0);

  tangent.reinit(second, 8);
  EXPECT_EQ(&tangent.serial().get_sparsity_pattern(), &second);
  EXPECT_EQ(tangent.serial().n_nonzero_elements(), n);
}
