#include <coshell/model/rigid_body_modes.h>
#include <coshell/solvers/linear_static.h>

#include <cmath>
#include <stdexcept>

namespace coshell::solvers
{
  using namespace dealii;

  LinearStatic::LinearStatic(const model::ShellModel         &model,
                             const AffineConstraints<double> &constraints)
      : model_(model), constraints_(constraints)
  {
    model::check_supports(model_, constraints_);
    allocate_stiffness();
    load_.reinit(model_.n_dofs());
  }

  void LinearStatic::allocate_stiffness()
  {
    model_.make_sparsity(constraints_, sparsity_);
    stiffness_.reinit(sparsity_);
  }

  void LinearStatic::assemble(const model::Loads &loads, std::ostream &log)
  {
    if (stiffness_.empty()) // released by the last solve()
      allocate_stiffness();
    model_.assemble_stiffness(constraints_, stiffness_);
    load_ = 0;
    loads.assemble(model_, load_, log);
    constraints_.condense(load_);
    regularize_inactive_dofs();
  }

  void LinearStatic::regularize_inactive_dofs()
  {
    double       diagonal_sum = 0;
    unsigned int n_active     = 0;
    for (unsigned int i = 0; i < stiffness_.m(); ++i)
      if (stiffness_.diag_element(i) != 0)
      {
        diagonal_sum += std::abs(stiffness_.diag_element(i));
        ++n_active;
      }
    const double typical = n_active > 0 ? diagonal_sum / n_active : 1.0;
    n_inactive_dofs_     = 0;
    for (unsigned int i = 0; i < stiffness_.m(); ++i)
      if (stiffness_.diag_element(i) == 0)
      {
        if (load_[i] != 0)
          throw std::runtime_error(
              "a load acts on DoF " + std::to_string(i) +
              ", which no element stiffens (is the membrane or bending part "
              "switched off?)");
        stiffness_.diag_element(i) = typical;
        ++n_inactive_dofs_;
      }
  }

  Vector<double> LinearStatic::solve(LinearSolver &solver)
  {
    if (stiffness_.empty())
      throw std::logic_error("LinearStatic::solve() needs assemble() first");
    Vector<double> solution(model_.n_dofs());
    if (solver.uses_near_null_space())
    {
      const auto modes = model::rigid_body_modes(model_);
      solver.set_near_null_space({modes.begin(), modes.end()});
    }
    // Nothing reads K after the solve: at millions of DoFs, freeing it
    // before the AMG set-up is what lets the largest problems fit.
    solver.factorize(stiffness_, true,
                     [this]
                     {
                       stiffness_.clear();
                       sparsity_.reinit(0, 0, 0);
                     });
    solver.solve(solution, load_);
    constraints_.distribute(solution);
    for (const double value : solution)
      if (!std::isfinite(value))
        throw std::runtime_error("the linear solve produced non-finite "
                                 "values: the stiffness is singular (missing "
                                 "boundary conditions?)");
    return solution;
  }

  unsigned int LinearStatic::n_inactive_dofs() const
  {
    return n_inactive_dofs_;
  }
} // namespace coshell::solvers
