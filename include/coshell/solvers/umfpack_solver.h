#pragma once

#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>

#include <memory>

namespace coshell::solvers
{
  /// Sparse LU factorization with SuiteSparse UMFPACK for general
  /// (non-symmetric or indefinite) matrices, such as the consistent
  /// co-rotational tangent. Unlike deal.II's SparseDirectUMFPACK, the
  /// symbolic analysis (column ordering, elimination tree) is kept per
  /// sparsity pattern, so the Newton iterations of a nonlinear solve only
  /// refactor numerically.
  class UmfpackSolver
  {
  public:
    UmfpackSolver();
    ~UmfpackSolver();

    /// Throws std::runtime_error if the matrix is singular.
    void factorize(const dealii::SparseMatrix<double> &matrix);
    void solve(dealii::Vector<double>       &x,
               const dealii::Vector<double> &b) const;
    /// True once factorize() succeeded on a matrix of this size.
    bool has_factors_of_size(unsigned int n_rows) const;
    /// x = (L U)^-1 b with the factors of the last factorized matrix and no
    /// iterative refinement: the preconditioner of a nearby matrix.
    void apply_factors(dealii::Vector<double>       &x,
                       const dealii::Vector<double> &b) const;

  private:
    struct Data;
    std::unique_ptr<Data> data_;
  };
} // namespace coshell::solvers
