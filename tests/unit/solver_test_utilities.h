#pragma once

// Small tools shared by the solver unit tests (Newton, path following,
// time integration): a direct linear solver and an independent root.

#include <coshell/solvers/linear_solver.h>

#include <deal.II/base/parameter_handler.h>

#include <cmath>

namespace coshell::solvers::testing
{
  /// One LinearSolver with Method = umfpack (any tangent, symmetric or
  /// not), shared by the tests of one executable.
  inline LinearSolver &umfpack()
  {
    static LinearSolver      solver;
    dealii::ParameterHandler prm;
    LinearSolver::declare_parameters(prm);
    prm.enter_subsection("Linear solver");
    prm.set("Method", "umfpack");
    prm.leave_subsection();
    solver.parse_parameters(prm);
    return solver;
  }

  /// The root of x + c x^3 = load (c >= 0) by bisection, independent of
  /// Newton.
  inline double hardening_root(double load, double c)
  {
    double low = -std::abs(load) - 1, high = std::abs(load) + 1;
    for (int i = 0; i < 200; ++i)
    {
      const double mid                                = 0.5 * (low + high);
      (mid + c * mid * mid * mid < load ? low : high) = mid;
    }
    return 0.5 * (low + high);
  }
} // namespace coshell::solvers::testing
