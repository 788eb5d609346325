#pragma once

#include <coshell/base/nonlinear_problem.h>
#include <coshell/solvers/linear_solver.h>
#include <coshell/solvers/newton.h>

#include <deal.II/base/parameter_handler.h>

#include <functional>
#include <ostream>
#include <string>

namespace coshell::solvers
{
  /// Implicit time integration of M(q) qdd + f_int(q, qd) = f_ext(t) on
  /// R^3 x SO(3) per vertex (prm subsection "Time integration"):
  /// - generalized alpha: the Lie-group generalized-alpha scheme of Bruls &
  ///   Cardona (2010) in the form of Arnold & Bruls (2007): equilibrium at
  ///   t_{n+1}, rotations updated R_{n+1} = R_n exp(h Delta Omega),
  ///   second order, numerical damping set by the spectral radius rho_inf;
  /// - implicit euler: backward Euler on the same group, first order;
  /// - linearized implicit euler: one Newton correction of backward Euler
  ///   per step (Baraff & Witkin 1998, as SOFA and the seed paper).
  /// Time steps are cut on Newton failure and grown after easy steps.
  /// With Lie group = SE3 the same schemes run on SE(3) per vertex: the
  /// step increments and rates are the problem's body-frame ones.
  class TimeIntegration
  {
  public:
    static void declare_parameters(dealii::ParameterHandler &prm);
    /// Throws std::invalid_argument naming the parameter.
    void parse_parameters(dealii::ParameterHandler &prm);

    struct StepRecord
    {
      unsigned int step; ///< counted over the whole run
      double       time, dt;
      unsigned int iterations;
    };
    using StepObserver = std::function<void(const StepRecord &)>;
    /// Judges a converged step before it is accepted: an empty string
    /// accepts it, a reason rejects it, and the step is cut as after a
    /// Newton failure (the energy guard, Energy growth limit).
    using StepCheck = std::function<std::string(const StepRecord &)>;

    /// What the scheme carries from one step to the next besides the
    /// problem's state: generalized alpha's pseudo-acceleration a_n and the
    /// step controller's next size. Given to run(), it is updated after
    /// every accepted step, and a run started from a filled one continues
    /// exactly where the run that filled it stood (checkpoint and restart)
    /// instead of starting afresh (a consistent initial acceleration).
    struct Carry
    {
      dealii::Vector<double> pseudo_acceleration;
      double                 step_size = 0; ///< s; 0: not filled
      bool                   filled() const
      {
        return step_size > 0;
      }
    };
    using IterationObserver =
        std::function<void(unsigned int step, const NewtonIteration &)>;

    /// Integrates from the problem's current state (its velocities are
    /// the initial ones; the initial acceleration is made consistent)
    /// from 'start' to 'end'. 'first_step' numbers the steps. Returns the
    /// number of steps taken. Throws NewtonFailure.
    unsigned int run(base::EvolutionProblem  &problem,
                     LinearSolver            &linear_solver,
                     const NewtonParameters  &newton,
                     double                   start,
                     double                   end,
                     unsigned int             first_step,
                     const StepObserver      &on_step,
                     const IterationObserver &on_iteration,
                     std::ostream            &log,
                     Carry                   *carry      = nullptr,
                     const StepCheck         &step_check = {}) const;

    const std::string &method() const;
    /// Method = linearized implicit euler: one correction a step, no
    /// evaluation at the step's end.
    bool   linearized() const;
    double end_time() const;
    /// Energy growth limit (dimensionless); 0: the guard is off.
    double energy_growth_limit() const;
    /// A warning for a combination of settings known to accept steps that
    /// create energy (generalized alpha on R3xSO3 at little damping with
    /// the energy guard off); empty otherwise.
    std::string known_risk() const;
    /// Lie group = SE3: body-frame translations (ShellState).
    bool se3() const;

    /// The rates of one scheme as functions of the step increment.
    struct Scheme;

  private:
    /// A restart's first step size: the checkpoint's carried size clipped
    /// to the Minimum/Maximum time step in force (logged when it is).
    double resumed_step_size(double carried, std::ostream &log) const;

    std::string  method_              = "generalized alpha";
    bool         se3_                 = false;
    double       time_step_           = 1e-3;
    double       min_time_step_       = 1e-9;
    double       max_time_step_       = 1e-3;
    double       spectral_radius_     = 0.9;
    double       end_time_            = 1;
    unsigned int max_step_cuts_       = 12;
    unsigned int easy_iterations_     = 4;
    double       growth_factor_       = 1.5;
    double       cut_factor_          = 0.5;
    double       progress_interval_   = 5;
    double       energy_growth_limit_ = 1;

    void initial_acceleration(base::EvolutionProblem &problem,
                              LinearSolver           &linear_solver) const;
  };
} // namespace coshell::solvers
