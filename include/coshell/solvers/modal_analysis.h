#pragma once

#include <coshell/solvers/linear_solver.h>

#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>

#include <vector>

namespace coshell::solvers
{
  /// The eigenpairs K x = lambda M x closest to 'shift' (lambda = omega^2),
  /// by ARPACK's symmetric shift-invert Lanczos with (K - shift M)^-1
  /// applied through 'linear_solver'. K and M must be symmetric, M
  /// positive semi-definite (rows of constrained DoFs: zero in M, so their
  /// spurious eigenvalues go to infinity). Returns the eigenvalues in
  /// increasing order and the M-normalized vectors. Throws
  /// std::runtime_error when ARPACK fails.
  void lowest_modes(const dealii::SparseMatrix<double>  &stiffness,
                    const dealii::SparseMatrix<double>  &mass,
                    LinearSolver                        &linear_solver,
                    double                               shift,
                    unsigned int                         n_modes,
                    std::vector<double>                 &eigenvalues,
                    std::vector<dealii::Vector<double>> &modes);
} // namespace coshell::solvers
