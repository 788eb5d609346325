#include <coshell/solvers/modal_analysis.h>

#include <deal.II/lac/arpack_solver.h>
#include <deal.II/lac/solver_control.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace coshell::solvers
{
  using namespace dealii;

  namespace
  {
    /// (K - shift M)^-1 as an operator, from one factorization.
    struct ShiftedInverse
    {
      LinearSolver &solver;
      void          vmult(Vector<double> &x, const Vector<double> &b) const
      {
        solver.solve(x, b);
      }
    };
  } // namespace

  void lowest_modes(const SparseMatrix<double>  &stiffness,
                    const SparseMatrix<double>  &mass,
                    LinearSolver                &linear_solver,
                    double                       shift,
                    unsigned int                 n_modes,
                    std::vector<double>         &eigenvalues,
                    std::vector<Vector<double>> &modes)
  {
    SparseMatrix<double> shifted(stiffness.get_sparsity_pattern());
    shifted.copy_from(stiffness);
    if (shift != 0)
      shifted.add(-shift, mass);
    linear_solver.factorize(shifted, true);
    const ShiftedInverse inverse{linear_solver};

    const unsigned int n = stiffness.m();
    if (n_modes + 1 >= n)
      throw std::runtime_error("Modal analysis: asked for " +
                               std::to_string(n_modes) +
                               " modes of a system "
                               "with " +
                               std::to_string(n) + " unknowns");
    SolverControl                control(1000, 1e-10);
    ArpackSolver::AdditionalData data(std::min(n - 1, 2 * n_modes + 10),
                                      ArpackSolver::largest_magnitude, true);
    ArpackSolver                 arpack(control, data);
    arpack.set_shift(shift);
    std::vector<std::complex<double>> values(n_modes);
    std::vector<Vector<double>>       vectors(n_modes, Vector<double>(n));
    try
    {
      arpack.solve(stiffness, mass, inverse, values, vectors, n_modes);
    }
    catch (const std::exception &error)
    {
      throw std::runtime_error(std::string("Modal analysis: ARPACK failed: ") +
                               error.what());
    }
    std::vector<unsigned int> order(n_modes);
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(),
              [&](unsigned int a, unsigned int b)
              { return values[a].real() < values[b].real(); });
    eigenvalues.clear();
    modes.clear();
    for (const unsigned int k : order)
    {
      eigenvalues.push_back(values[k].real());
      Vector<double> &mode = modes.emplace_back(vectors[k]);
      Vector<double>  mass_times(n);
      mass.vmult(mass_times, mode);
      mode /= std::sqrt(std::max(mode * mass_times, 1e-300));
    }
  }
} // namespace coshell::solvers
