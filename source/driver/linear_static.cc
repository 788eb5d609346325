#include <coshell/base/parallel_environment.h>
#include <coshell/driver/linear_static.h>
#include <coshell/model/rigid_body_modes.h>

#include <cmath>
#include <stdexcept>

namespace coshell::driver
{
  using namespace dealii;

  LinearStatic::LinearStatic(const model::ShellModel         &model,
                             const AffineConstraints<double> &constraints,
                             const IndexSet                  &distributed_rows)
      : model_(model), constraints_(constraints),
        distributed_rows_(distributed_rows)
  {
    model::check_supports(model_, constraints_);
    allocate_stiffness();
    load_.reinit(model_.n_dofs());
  }

  bool LinearStatic::distributed_stiffness() const
  {
    return distributed_rows_.size() > 0;
  }

  bool LinearStatic::stiffness_allocated() const
  {
    return distributed_stiffness() ? distributed_stiffness_ != nullptr
                                   : !stiffness_.empty();
  }

  void LinearStatic::allocate_stiffness()
  {
    if (distributed_stiffness())
    {
      // The matrix copies the graph: the pattern goes at once.
      TrilinosWrappers::SparsityPattern pattern;
      model_.make_distributed_sparsity(constraints_, distributed_rows_,
                                       pattern);
      distributed_stiffness_ =
          std::make_unique<TrilinosWrappers::SparseMatrix>();
      distributed_stiffness_->reinit(pattern);
      return;
    }
    model_.make_sparsity(constraints_, sparsity_);
    stiffness_.reinit(sparsity_);
  }

  void LinearStatic::assemble(const model::Loads &loads, std::ostream &log)
  {
    if (!stiffness_allocated()) // released by the last solve()
      allocate_stiffness();
    load_ = 0;
    loads.assemble(model_, load_, log);
    constraints_.condense(load_);
    if (distributed_stiffness())
    {
      model_.assemble_stiffness(constraints_, *distributed_stiffness_);
      regularize_inactive_dofs(*distributed_stiffness_, distributed_rows_);
      distributed_stiffness_->compress(VectorOperation::insert);
    }
    else
    {
      model_.assemble_stiffness(constraints_, stiffness_);
      regularize_inactive_dofs(stiffness_, complete_index_set(stiffness_.m()));
    }
  }

  template<typename Matrix>
  void LinearStatic::regularize_inactive_dofs(Matrix         &matrix,
                                              const IndexSet &rows)
  {
    // [sum of |diagonal| over stiffened rows, their number, the number of
    // unstiffened rows, then per rank the first unstiffened row that carries
    // a load + 1], summed over the ranks (each row lives on one rank), so
    // that every rank stops with the same message.
    Vector<double> totals(3 + base::n_ranks());
    double        &loaded_row = totals[3 + base::this_rank()];
    for (const auto i : rows)
      if (const double diagonal = matrix.diag_element(i); diagonal != 0)
      {
        totals[0] += std::abs(diagonal);
        totals[1] += 1;
      }
      else
      {
        totals[2] += 1;
        if (load_[i] != 0 && loaded_row == 0)
          loaded_row = i + 1.0;
      }
    base::sum_over_ranks(totals);
    for (unsigned int rank = 0; rank < base::n_ranks(); ++rank)
      if (const double row = totals[3 + rank]; row != 0)
        throw std::runtime_error(
            "a load acts on DoF " + std::to_string(static_cast<long>(row) - 1) +
            ", which no element stiffens (is the membrane or bending part "
            "switched off?)");
    const double typical = totals[1] > 0 ? totals[0] / totals[1] : 1.0;
    n_inactive_dofs_     = static_cast<unsigned int>(totals[2]);
    if (n_inactive_dofs_ > 0)
      for (const auto i : rows)
        if (matrix.diag_element(i) == 0)
          matrix.set(i, i, typical);
  }

  Vector<double> LinearStatic::solve(solvers::LinearSolver &solver)
  {
    if (!stiffness_allocated())
      throw std::logic_error("LinearStatic::solve() needs assemble() first");
    Vector<double> solution(model_.n_dofs());
    if (solver.uses_near_null_space())
    {
      const auto modes = model::rigid_body_modes(model_);
      solver.set_near_null_space({modes.begin(), modes.end()});
    }
    if (distributed_stiffness())
    {
      // Released before factorize(), so that a failed set-up leaves no
      // moved-from matrix that looks assembled.
      const auto stiffness = std::move(distributed_stiffness_);
      solver.factorize(std::move(*stiffness));
    }
    else
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
} // namespace coshell::driver
