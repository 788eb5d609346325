#pragma once

// Scalar contact potentials of the gap g (distance minus the offsets) and
// the projection of a small symmetric matrix onto the positive
// semi-definite cone. Pure functions; no state.

#include <array>
#include <vector>

namespace coshell::contact
{
  /// A function of one variable with its first two derivatives.
  struct ScalarDerivatives
  {
    double value = 0, first = 0, second = 0;
  };

  /// The log barrier of incremental potential contact (Li et al. 2020),
  /// b(g) = -(g - g_hat)^2 ln(g / g_hat) for 0 < g < g_hat and 0 beyond:
  /// C2 at g_hat, infinite as g -> 0. Units: length^2 (times a stiffness
  /// in force / length gives an energy).
  ScalarDerivatives log_barrier(double gap, double activation_distance);

  /// A C2 penalty on the penetration x = -g: x^3 / (6 eps) for 0 <= x <=
  /// eps, x^2 / 2 - eps x / 2 + eps^2 / 6 beyond, 0 for g >= 0. Units:
  /// length^2.
  ScalarDerivatives smoothed_penalty(double gap, double smoothing);

  /// The symmetric n x n matrix (row-major) with its negative eigenvalues
  /// set to zero (cyclic Jacobi rotations). Newton on a barrier energy
  /// needs a positive semi-definite tangent per pair (Teran et al. 2005,
  /// as IPC does).
  void project_to_positive_semidefinite(std::vector<double> &matrix,
                                        unsigned int         n);
} // namespace coshell::contact
