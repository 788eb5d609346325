#pragma once

#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>

#include <memory>

namespace coshell::solvers
{
  /// Sparse Cholesky factorization of a symmetric positive definite matrix
  /// with SuiteSparse CHOLMOD (supernodal), which deal.II does not wrap.
  /// The fill-reducing ordering and symbolic analysis are computed once per
  /// sparsity pattern and reused; each factorize() then only refactors
  /// numerically.
  class CholmodSolver
  {
  public:
    CholmodSolver();
    ~CholmodSolver();

    /// Throws std::runtime_error if the matrix is not positive definite.
    void factorize(const dealii::SparseMatrix<double> &matrix);
    void solve(dealii::Vector<double>       &x,
               const dealii::Vector<double> &b) const;
    /// True once factorize() succeeded on a matrix of this size (and the
    /// last attempt did not fail): solve() then applies those factors.
    bool has_factors_of_size(unsigned int n_rows) const;

  private:
    struct Data;
    std::unique_ptr<Data> data_;
  };
} // namespace coshell::solvers
