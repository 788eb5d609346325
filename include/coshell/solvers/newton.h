#pragma once

#include <coshell/base/nonlinear_problem.h>
#include <coshell/solvers/linear_solver.h>

#include <deal.II/base/parameter_handler.h>

#include <functional>
#include <stdexcept>
#include <string>

namespace coshell::solvers
{
  /// Thrown when Newton fails (divergence, iteration limit, bad solve), or
  /// when a step cannot be completed even after cutting it.
  class NewtonFailure : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };

  /// x with 6 significant digits, for messages.
  std::string short_number(double x);

  /// Convergence and line-search settings (prm subsection "Nonlinear
  /// solver").
  struct NewtonParameters
  {
    unsigned int max_iterations      = 30;
    double       residual_tolerance  = 1e-7;
    double       energy_tolerance    = 1e-16;
    double       increment_tolerance = 1e-8;
    /// Largest entry of the Newton correction that counts as converged
    /// (0: not used).
    double correction_tolerance = 0;
    /// Largest entry of the correction per unit time step that counts as
    /// converged in dynamics (0: not used); in statics it is not used.
    double velocity_tolerance = 0;
    bool   line_search        = false;
    /// How the line search judges a scale.
    enum class LineSearchRule
    {
      energy_slope, ///< Crisfield's secant steps on du.r
      armijo        ///< backtracking on the problem's energy()
    };
    LineSearchRule line_search_rule = LineSearchRule::energy_slope;
    /// |r| / scale above this counts as divergence.
    double divergence_limit = 1e8;
    /// Climbing corrections in an attempt before Newton asks the problem
    /// for a convex tangent (base::NonlinearProblem::use_convex_tangent()).
    unsigned int climbs_before_convex_tangent = 3;

    /// Declares the entries in the current subsection.
    static void declare_parameters(dealii::ParameterHandler &prm);
    void        parse_parameters(dealii::ParameterHandler &prm);
  };

  /// One Newton iteration as the history records it.
  struct NewtonIteration
  {
    unsigned int iteration;
    double       relative_residual; ///< |r| / force scale
    double       correction_norm;   ///< 0 on the converged evaluation
    double       relative_energy;   ///< |du.r| / |du_0.r_0|
  };

  /// Newton-Raphson on a base::NonlinearProblem. Knows no physics: it
  /// evaluates, factorizes, solves, filters the step (line search, admissible
  /// fraction) and judges convergence against the problem's force scale.
  class Newton
  {
  public:
    using Observer = std::function<void(const NewtonIteration &)>;

    Newton(const NewtonParameters &parameters, LinearSolver &linear_solver);

    /// Iterates from the problem's current state until converged; returns
    /// the number of corrections applied. Throws NewtonFailure, leaving the
    /// problem wherever it got.
    /// 'time_step' (s) scales the velocity tolerance; 0 in statics.
    unsigned int solve(base::NonlinearProblem &problem,
                       const Observer         &observer  = Observer(),
                       double                  time_step = 0) const;

    /// Exactly one correction from the current state, no convergence test
    /// (the linearized implicit scheme). Returns the relative residual
    /// before the correction. Throws NewtonFailure when the residual is not
    /// finite or a prescribed move was blocked (a jam).
    double single_correction(base::NonlinearProblem &problem,
                             const Observer &observer = Observer()) const;

    /// Assembles the tangent at the problem's present state and
    /// factorizes it as an iteration would, without a correction: the
    /// linear solver's kept factors are then the present state's (for how
    /// a converged state answers a change of its data). The state is not
    /// changed.
    void factorize_tangent(base::NonlinearProblem &problem) const;

  private:
    NewtonParameters parameters_;
    LinearSolver    &linear_solver_;
    /// The tangent every solve assembles into, kept from one solve to the
    /// next: a time step's solve would otherwise allocate and zero a
    /// matrix of the whole pattern before assembling (and zeroing) it.
    /// Made again only when the problem's pattern changes.
    mutable base::TangentMatrix tangent_;

    /// Lets the problem assemble only what the linear solver reads.
    void assemble_for_solver(const base::NonlinearProblem &problem,
                             base::TangentMatrix          &tangent) const;
    /// Factorizes the tangent and solves for the correction (distributed).
    dealii::Vector<double>
    correction(base::NonlinearProblem       &problem,
               base::TangentMatrix          &tangent,
               const dealii::Vector<double> &residual) const;
    /// The line search's scale of a correction; whether it accepted an
    /// evaluated trial (left applied), and whether that trial assembled
    /// the tangent.
    struct LineSearch
    {
      double scale        = 1;
      bool   accepted     = false;
      bool   with_tangent = false;
    };
    LineSearch line_search(base::NonlinearProblem       &problem,
                           const dealii::Vector<double> &residual,
                           const dealii::Vector<double> &correction,
                           dealii::Vector<double>       &trial_residual,
                           base::TangentMatrix          *tangent) const;
    LineSearch armijo_search(base::NonlinearProblem       &problem,
                             double                        energy_at_zero,
                             double                        slope_at_zero,
                             const dealii::Vector<double> &correction,
                             dealii::Vector<double>       &trial_residual,
                             base::TangentMatrix          *tangent,
                             double                       &trial_energy) const;
    bool       apply_correction(base::NonlinearProblem &problem,
                                const LineSearch       &search,
                                bool                    next_with_tangent,
                                dealii::Vector<double> &du,
                                dealii::Vector<double> &residual,
                                dealii::Vector<double> &trial_residual) const;
    /// What a solve carries from one iteration to the next (newton.cc).
    struct Iterate;
    /// The line search the parameters ask for; Crisfield's where the
    /// problem has no energy or the correction does not descend.
    LineSearch search_line(base::NonlinearProblem       &problem,
                           Iterate                      &it,
                           const dealii::Vector<double> &correction,
                           base::TangentMatrix          *tangent) const;
    /// The residual's norm relative to the force scale, fed to the
    /// convergence prediction; throws when it is not finite or diverged.
    double judge_residual(base::NonlinearProblem &problem, Iterate &it) const;
    /// One correction: solve, step filter, line search, convergence
    /// measures, and the corrected iterate (evaluated if a trial was kept).
    /// A correction that climbs the energy once too often is dropped
    /// instead, unapplied and unobserved, when the problem can switch to
    /// its convex tangent: the next iteration corrects the same iterate.
    void correct(base::NonlinearProblem &problem,
                 Iterate                &it,
                 unsigned int            iteration,
                 double                  relative_residual,
                 double                  correction_tolerance,
                 const Observer         &observer) const;
  };

  /// Step-size policy shared by load stepping, arc length and time
  /// stepping: cut a failed step, grow again after easy ones.
  class StepController
  {
  public:
    struct Settings
    {
      double       initial = 0.1, minimum = 1e-9, maximum = 0.1;
      unsigned int max_consecutive_cuts = 12;
      /// A step that took at most this many iterations is "easy".
      unsigned int easy_iterations = 6;
      double       growth_factor = 2, cut_factor = 0.5;
    };

    explicit StepController(const Settings &settings);

    /// The next step size to try.
    double size() const;
    /// After a converged step that took 'iterations'.
    void success(unsigned int iterations);
    /// After a failed attempt of size 'attempted': cuts, or throws
    /// NewtonFailure "<step> failed after N step cuts: <cause>" once cuts
    /// run out or the size falls below the minimum.
    void failure(double             attempted,
                 const std::string &step,
                 const std::string &cause);

  private:
    Settings     settings_;
    double       size_;
    unsigned int cuts_ = 0;
  };
} // namespace coshell::solvers
