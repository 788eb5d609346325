#pragma once

#include <coshell/base/nonlinear_problem.h>
#include <coshell/solvers/linear_solver.h>
#include <coshell/solvers/newton.h>

#include <deal.II/base/parameter_handler.h>

#include <functional>
#include <ostream>
#include <string>
#include <vector>

namespace coshell::solvers
{
  /// Static equilibrium path of an base::EvolutionProblem from path parameter 0
  /// to 1: Newton under parameter (load or displacement) control with step
  /// cutting, or Crisfield's cylindrical arc-length method (prm subsection
  /// "Nonlinear solver", which also holds Newton's settings).
  class PathFollowing
  {
  public:
    static void declare_parameters(dealii::ParameterHandler &prm);
    void        parse_parameters(dealii::ParameterHandler &prm);

    /// Called after every converged step with (step, path parameter,
    /// Newton iterations).
    using StepObserver =
        std::function<void(unsigned int, double, unsigned int)>;
    /// Called for every Newton iteration with (step, iteration record).
    using IterationObserver =
        std::function<void(unsigned int, const NewtonIteration &)>;

    /// Follows the path (parameter control: stopping exactly at every
    /// parameter in 'stops'; arc length: until the parameter reaches the
    /// maximum or the step limit). Throws NewtonFailure.
    void run(base::EvolutionProblem    &problem,
             LinearSolver              &linear_solver,
             const std::vector<double> &stops,
             const StepObserver        &on_step,
             const IterationObserver   &on_iteration,
             std::ostream              &log) const;

    const std::string      &method() const;
    bool                    arc_length() const;
    const NewtonParameters &newton() const;

  private:
    std::string      method_               = "load control";
    unsigned int     load_steps_           = 10;
    unsigned int     max_step_cuts_        = 12;
    unsigned int     easy_iterations_      = 6;
    double           growth_factor_        = 2;
    double           cut_factor_           = 0.5;
    unsigned int     max_arc_length_steps_ = 200;
    double           max_load_factor_      = 1;
    NewtonParameters newton_;

    struct Run;
    void         parameter_control(Run &run) const;
    void         arc_length_path(Run &run) const;
    unsigned int arc_length_step(Run &run, double arc) const;
  };
} // namespace coshell::solvers
