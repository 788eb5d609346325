#include <coshell/solvers/newton.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>
#include <utility>
#include <vector>

namespace coshell::solvers
{
  using namespace dealii;

  std::string short_number(double x)
  {
    std::ostringstream out;
    out << std::setprecision(6) << x;
    return out.str();
  }

  namespace
  {
    bool is_finite(const Vector<double> &v)
    {
      return std::all_of(v.begin(), v.end(),
                         [](double x) { return std::isfinite(x); });
    }

    /// The smallest scale the line search takes.
    constexpr double smallest_line_search_scale = 0.1;
    /// Armijo's sufficient decrease: the share of the linear model's
    /// decrease a scale must achieve (Nocedal & Wright's usual 1e-4), and
    /// the halvings tried.
    constexpr double       armijo_decrease = 1e-4;
    constexpr unsigned int armijo_halvings = 10;
    /// Below this many round-offs of the energy, a decrease cannot be
    /// judged: the correction is taken whole.
    constexpr double energy_round_off =
        1e3 * std::numeric_limits<double>::epsilon();

    /// Why a step that ends with a prescribed move pending has failed.
    const std::string pending_move_note =
        "a prescribed move is still pending: an obstacle or a prescribed "
        "motion cannot reach its position (the shell is in its way: a jam)";

    /// What the last corrections of a failing attempt looked like: cut to
    /// the line search's floor, and climbing the energy (du.r < 0, the
    /// tangent indefinite along du). Their signature tells an indefinite
    /// tangent from a slow one in the failure message.
    class CorrectionRecord
    {
    public:
      void add(bool at_floor, bool climbing)
      {
        records_.push_back({at_floor, climbing});
      }
      std::string summary() const
      {
        const unsigned int n = std::min<std::size_t>(records_.size(), 10);
        unsigned int       at_floor = 0, climbing = 0;
        for (auto it = records_.end() - n; it != records_.end(); ++it)
        {
          at_floor += it->first;
          climbing += it->second;
        }
        if (at_floor == 0 && climbing == 0)
          return "";
        const std::string climbed =
            climbing == 0 ? ""
                          : std::to_string(climbing) +
                                " climbed the energy (du.r < 0: the tangent "
                                "is indefinite along them)";
        const std::string cut = at_floor == 0 ? ""
                                              : "the line search cut " +
                                                    std::to_string(at_floor) +
                                                    " to a tenth";
        return "; of the last " + std::to_string(n) + " corrections " +
               climbed + (climbing && at_floor ? " and " : "") + cut;
      }

    private:
      std::vector<std::pair<bool, bool>> records_;
    };

    /// Whether the coming evaluation will, by the quadratic model, end the
    /// solve: its tangent would be thrown away, so the residual comes
    /// first and the tangent only if the residual is not small after all.
    /// From the relative residuals r0 > r1 before and after a whole
    /// correction, and a whole correction since: r2 = C r1^2, C = r1 / r0^2.
    class ConvergencePrediction
    {
    public:
      explicit ConvergencePrediction(double tolerance) : tolerance_(tolerance)
      {
      }
      /// The residual of an iterate that a correction scaled by
      /// 'whole' ? 1 : less than 1 led to.
      void add(double relative_residual, bool whole)
      {
        older_ = whole ? last_ : 0;
        last_  = relative_residual;
      }
      bool expects_convergence(bool whole) const
      {
        if (!whole || older_ <= 0 || last_ >= older_ || last_ > 1e-2)
          return false;
        return last_ * last_ * last_ / (older_ * older_) <= tolerance_;
      }

    private:
      double tolerance_, older_ = 0, last_ = 0;
    };
  } // namespace

  void NewtonParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.declare_entry("Maximum iterations", "30", Patterns::Integer(1),
                      "Newton iterations per attempt of a step. Unit: "
                      "dimensionless (a count).");
    prm.declare_entry(
        "Residual tolerance", "1e-7", Patterns::Double(0),
        "Newton has converged when |r| <= tol * F, F the "
        "largest of the internal, external and inertia force norms (so a "
        "displacement-driven step with no external load is judged too), or "
        "when both Energy and Increment tolerances are met. Unit: "
        "dimensionless.");
    prm.declare_entry("Energy tolerance", "1e-16", Patterns::Double(0),
                      "Converged when |du.r| <= tol |du_0.r_0|, the energy "
                      "of the last correction relative to the first of the "
                      "step. Unit: dimensionless.");
    prm.declare_entry("Increment tolerance", "1e-8", Patterns::Double(0),
                      "Converged when |du| <= tol |sum of corrections in "
                      "the step|. Unit: dimensionless.");
    prm.declare_entry(
        "Correction tolerance", "0", Patterns::Double(0),
        "0 = not used. Newton "
        "has also converged when the largest entry of its correction, "
        "before the collision filter and the line search shorten it, is at "
        "most this: the distance Newton still expects to move (the "
        "criterion of Li et al. 2020, IPC, on the step's displacement). "
        "Where a stiff barrier leaves the residual converging slowly, this "
        "stops at a stated accuracy of the configuration. Unit: length "
        "for translations (mm in the IOL scenes), rad for rotations.");
    prm.declare_entry(
        "Velocity tolerance", "0", Patterns::Double(0),
        "0 = not used. In dynamics Newton has also converged when the "
        "largest entry of its correction, before the collision filter and "
        "the line search, divided by the time step is at most this (Li et "
        "al. 2020, IPC: a tolerance on the velocity the step still expects "
        "to change, so that the accuracy it stands for does not shrink with "
        "the step). Where Correction tolerance is set too, the larger of "
        "the two holds. Unit: length per second for translations (mm/s in "
        "the IOL scenes), rad/s for rotations.");
    prm.declare_entry("Line search", "false", Patterns::Bool(),
                      "Scale each Newton correction du by s so that "
                      "|du.r(s du)| <= 0.8 |du.r(0)| (secant steps on the "
                      "energy slope, Crisfield 1991). Off by default: on "
                      "large-rotation steps the full Newton step, though it "
                      "raises the residual at first, converges faster.");
    prm.declare_entry(
        "Line search rule", "energy slope",
        Patterns::Selection("energy slope|armijo"),
        "With Line search: energy slope = Crisfield's secant steps on "
        "du.r; armijo = backtracking on the incremental potential E (Li "
        "et al. 2020, IPC): from the whole correction (after the collision "
        "filter), halve the scale s until E(x + s du) <= E(x) - 1e-4 s "
        "du.r, at most 10 times. Armijo needs every contribution to have a "
        "potential (no follower pressure, no moments on finite rotations, "
        "no SE3 translations); otherwise, and for a correction that climbs "
        "the energy, the energy slope search is used. Unit: none (a "
        "choice).");
    prm.declare_entry(
        "Climbs before convex tangent", "3", Patterns::Integer(1),
        "After this many corrections of an attempt have "
        "climbed the energy (du.r < 0: the tangent is indefinite along "
        "them), Newton asks the problem for a convex tangent and, if it has "
        "one (contact with Projected tangent on stall), discards the "
        "correction and solves again with it. The IOL injection uses "
        "three: with 1 the switch comes too early and the fold takes more "
        "iterations. Unit: dimensionless (a count).");
    prm.declare_entry("Divergence limit", "1e8", Patterns::Double(1),
                      "A relative residual |r|/F above this ends the "
                      "attempt as diverged. Unit: dimensionless.");
  }

  void NewtonParameters::parse_parameters(ParameterHandler &prm)
  {
    max_iterations       = prm.get_integer("Maximum iterations");
    residual_tolerance   = prm.get_double("Residual tolerance");
    energy_tolerance     = prm.get_double("Energy tolerance");
    increment_tolerance  = prm.get_double("Increment tolerance");
    correction_tolerance = prm.get_double("Correction tolerance");
    velocity_tolerance   = prm.get_double("Velocity tolerance");
    line_search          = prm.get_bool("Line search");
    line_search_rule     = prm.get("Line search rule") == "armijo"
                               ? LineSearchRule::armijo
                               : LineSearchRule::energy_slope;
    divergence_limit     = prm.get_double("Divergence limit");
    climbs_before_convex_tangent =
        prm.get_integer("Climbs before convex tangent");
  }

  Newton::Newton(const NewtonParameters &parameters,
                 LinearSolver           &linear_solver)
      : parameters_(parameters), linear_solver_(linear_solver)
  {
  }

  /// What the linear solver does not read, the problem need not assemble:
  /// CHOLMOD reads a symmetric tangent's entries with column <= row only,
  /// and the cells' scatter is a sizeable part of a run
  /// (doc/performance/elements-and-assembly.md).
  void Newton::assemble_for_solver(const base::NonlinearProblem &problem,
                                   base::TangentMatrix          &tangent) const
  {
    if (!tangent.distributed())
      tangent.set_lower_only(
          linear_solver_.reads_lower_triangle(problem.symmetric_tangent()));
  }

  void Newton::factorize_tangent(base::NonlinearProblem &problem) const
  {
    base::TangentMatrix &tangent = tangent_;
    problem.reinit_tangent(tangent);
    assemble_for_solver(problem, tangent);
    Vector<double> residual(problem.sparsity().n_rows());
    problem.evaluate(residual, &tangent);
    linear_solver_.factorize(tangent, problem.symmetric_tangent());
  }

  Vector<double> Newton::correction(base::NonlinearProblem &problem,
                                    base::TangentMatrix    &tangent,
                                    const Vector<double>   &residual) const
  {
    linear_solver_.factorize(tangent, problem.symmetric_tangent());
    Vector<double> x(residual.size());
    // Refining the correction is what the next Newton iteration does:
    // UMFPACK's refinement steps would cost linear-solver time for
    // digits the next iteration supplies anyway.
    linear_solver_.solve(x, residual, LinearSolver::Refinement::none);
    problem.distribute(x);
    if (!is_finite(x))
      throw NewtonFailure("the linear solve gave non-finite values");
    return x;
  }

  namespace
  {
    /// Takes back a trial increment: the problem puts the iterate back
    /// exactly (end_trial()), and what the trial's evaluation changed.
    void undo_trial(base::NonlinearProblem &problem, Vector<double> &step)
    {
      step *= -1;
      problem.apply_increment(step);
      step *= -1;
      problem.end_trial();
    }
  } // namespace

  /// Crisfield's line search on the energy slope s(a) = du . r(x + a du):
  /// accept a when |s(a)| <= 0.8 |s(0)|, else take secant steps towards
  /// s = 0, keeping a in [0.1, 1]. Rejected trials are undone; an
  /// accepted one is left applied, with its residual in 'trial_residual',
  /// for the caller to keep or undo. The first trial assembles 'tangent'
  /// too if given: most line searches accept it (on the IOL injection),
  /// and its evaluation is then the next iteration's. Later
  /// trials are accepted less often, and assemble the residual alone.
  Newton::LineSearch Newton::line_search(base::NonlinearProblem &problem,
                                         const Vector<double>   &residual,
                                         const Vector<double>   &correction,
                                         Vector<double>         &trial_residual,
                                         base::TangentMatrix    *tangent) const
  {
    const double   slope_at_zero = correction * residual;
    double         a_low = 0, s_low = slope_at_zero, a = 1;
    Vector<double> step(correction.size());
    // The secant often comes back to a scale it has tried (the floor 0.1,
    // or 1 where the slope barely drops): that trial was rejected, and
    // evaluating the same iterate again gives the same slope. On the IOL
    // injection a tenth of the line searches did so, 2 evaluations each.
    std::vector<std::pair<double, double>> rejected;
    for (unsigned int trial = 0; trial < 4; ++trial)
    {
      const auto tried = std::find_if(rejected.begin(), rejected.end(),
                                      [a](const auto &scale_slope)
                                      { return scale_slope.first == a; });
      double     slope = tried == rejected.end() ? 0 : tried->second;
      if (tried == rejected.end())
      {
        step.equ(a, correction);
        problem.begin_trial();
        problem.apply_increment(step);
        base::TangentMatrix *trial_tangent = trial == 0 ? tangent : nullptr;
        problem.evaluate(trial_residual, trial_tangent);
        slope = correction * trial_residual;
        if (std::isfinite(slope) &&
            std::abs(slope) <= 0.8 * std::abs(slope_at_zero))
          return {a, true, trial_tangent != nullptr};
        undo_trial(problem, step);
        rejected.emplace_back(a, slope);
      }
      if (!std::isfinite(slope))
      {
        a = 0.5 * (a_low + a);
        continue;
      }
      const double secant = a_low + (a - a_low) * s_low / (s_low - slope);
      a_low               = a;
      s_low               = slope;
      a                   = std::clamp(std::isfinite(secant) ? secant : 1.0,
                     smallest_line_search_scale, 1.0);
    }
    return {a, false, false};
  }

  /// Armijo's backtracking on the problem's energy: the whole correction,
  /// then halves, until the energy drops by at least armijo_decrease of
  /// the linear model's prediction s du.r ('slope_at_zero' = du.r). As
  /// line_search(): rejected
  /// trials are undone, an accepted one is left applied with its residual
  /// in 'trial_residual' (and its energy in 'trial_energy'), the first
  /// trial assembles 'tangent' if given.
  Newton::LineSearch Newton::armijo_search(base::NonlinearProblem &problem,
                                           const double          energy_at_zero,
                                           const double          slope_at_zero,
                                           const Vector<double> &correction,
                                           Vector<double>       &trial_residual,
                                           base::TangentMatrix  *tangent,
                                           double &trial_energy) const
  {
    Vector<double> step(correction.size());
    double         a = 1;
    for (unsigned int trial = 0; trial <= armijo_halvings; ++trial, a *= 0.5)
    {
      step.equ(a, correction);
      problem.begin_trial();
      problem.apply_increment(step);
      base::TangentMatrix *trial_tangent = trial == 0 ? tangent : nullptr;
      problem.evaluate(trial_residual, trial_tangent);
      trial_energy = problem.energy();
      if (std::isfinite(trial_energy) &&
          trial_energy <= energy_at_zero - armijo_decrease * a * slope_at_zero)
        return {a, true, trial_tangent != nullptr};
      undo_trial(problem, step);
    }
    return {2 * a, false, false};
  }

  /// Applies the correction du, scaled already: keeps the line search's
  /// accepted trial, which is at x + du, if its evaluation is the kind the
  /// next iteration makes (with the tangent or without), and returns true;
  /// else undoes the trial, applies du and returns false. Keeping a trial
  /// of the other kind would change the path: an evaluation moves
  /// obstacles that are catching up with their motion, so evaluating the
  /// same iterate again is not the same as evaluating it once.
  bool Newton::apply_correction(base::NonlinearProblem &problem,
                                const LineSearch       &search,
                                bool                    next_with_tangent,
                                Vector<double>         &du,
                                Vector<double>         &residual,
                                Vector<double>         &trial_residual) const
  {
    if (search.accepted && search.with_tangent == next_with_tangent)
    {
      problem.keep_trial();
      residual.swap(trial_residual);
      return true;
    }
    if (search.accepted)
      undo_trial(problem, du);
    problem.apply_increment(du);
    return false;
  }

  /// What a solve carries from one iteration to the next.
  struct Newton::Iterate
  {
    Iterate(base::NonlinearProblem &problem,
            double                  residual_tolerance,
            base::TangentMatrix    &tangent)
        : tangent(tangent), residual(problem.sparsity().n_rows()),
          trial_residual(residual.size()), step_increment(residual.size()),
          prediction(residual_tolerance)
    {
      problem.reinit_tangent(tangent);
    }

    base::TangentMatrix &tangent;
    Vector<double>       residual, trial_residual;
    /// The sum of the corrections applied in this solve.
    Vector<double> step_increment;
    /// The energy |du.r| of the first correction, the yardstick of the
    /// energy tolerance.
    double           first_energy     = 0;
    bool             correction_small = false;
    CorrectionRecord corrections;
    /// Corrections that climbed the energy.
    unsigned int          climbs = 0;
    ConvergencePrediction prediction;
    /// The last correction was applied whole (no filter, no line search).
    bool whole_correction = false;
    /// The line search's accepted trial was kept: it evaluated the iterate.
    bool evaluated = false;
    /// The problem's energy at the iterate, if the kept trial gave it
    /// (NaN: not known yet).
    double energy = std::numeric_limits<double>::quiet_NaN();
  };

  Newton::LineSearch Newton::search_line(base::NonlinearProblem &problem,
                                         Iterate                &it,
                                         const Vector<double>   &correction,
                                         base::TangentMatrix    *tangent) const
  {
    const double slope = correction * it.residual;
    if (parameters_.line_search_rule ==
            NewtonParameters::LineSearchRule::armijo &&
        slope > 0)
    {
      const double energy =
          std::isfinite(it.energy) ? it.energy : problem.energy();
      it.energy = std::numeric_limits<double>::quiet_NaN();
      if (std::isfinite(energy))
      {
        // A decrease lost in the energy's round-off cannot be judged.
        if (slope <= energy_round_off * std::abs(energy))
          return {};
        double     trial_energy = 0;
        LineSearch search =
            armijo_search(problem, energy, slope, correction, it.trial_residual,
                          tangent, trial_energy);
        if (search.accepted)
          it.energy = trial_energy;
        return search;
      }
    }
    it.energy = std::numeric_limits<double>::quiet_NaN();
    return line_search(problem, it.residual, correction, it.trial_residual,
                       tangent);
  }

  unsigned int Newton::solve(base::NonlinearProblem &problem,
                             const Observer         &observer,
                             const double            time_step) const
  {
    const double correction_tolerance =
        std::max(parameters_.correction_tolerance,
                 parameters_.velocity_tolerance * time_step);
    problem.begin_solve();
    Iterate it(problem, parameters_.residual_tolerance, tangent_);
    assemble_for_solver(problem, it.tangent);
    for (unsigned int iteration = 0;; ++iteration)
    {
      const bool last_expected =
          it.correction_small ||
          it.prediction.expects_convergence(it.whole_correction);
      if (!it.evaluated)
        problem.evaluate(it.residual, last_expected ? nullptr : &it.tangent);
      it.evaluated = false;
      // Throws when the residual is not finite or has diverged.
      const double relative_residual = judge_residual(problem, it);
      // While a prescribed increment is pending the residual holds its
      // effect on the free unknowns, which no force measures yet.
      const bool pending = problem.prescribed_increment_pending();
      // Converged when the residual is small, or when the last correction
      // has dropped to round-off in both norm and energy: very stiff
      // membranes leave a round-off floor in the residual.
      if (!pending && (relative_residual <= parameters_.residual_tolerance ||
                       it.correction_small))
      {
        if (observer)
          observer({iteration, relative_residual, 0, 0});
        return iteration;
      }
      if (last_expected)
        problem.evaluate(it.residual, &it.tangent); // not the last after all
      if (iteration == parameters_.max_iterations)
        throw NewtonFailure("Newton did not converge in " +
                            std::to_string(parameters_.max_iterations) +
                            " iterations (relative residual " +
                            short_number(relative_residual) +
                            it.corrections.summary() + ")" +
                            (pending ? "; " + pending_move_note : "") +
                            problem.failure_context());
      correct(problem, it, iteration, relative_residual, correction_tolerance,
              observer);
    }
  }

  double Newton::judge_residual(base::NonlinearProblem &problem,
                                Iterate                &it) const
  {
    const double relative_residual =
        it.residual.l2_norm() / std::max(problem.force_scale(), 1e-300);
    it.prediction.add(relative_residual, it.whole_correction);
    if (!std::isfinite(it.residual.l2_norm()) ||
        (!problem.prescribed_increment_pending() &&
         relative_residual > parameters_.divergence_limit))
      throw NewtonFailure("Newton diverged (relative residual " +
                          short_number(relative_residual) + ")" +
                          problem.failure_context());
    return relative_residual;
  }

  void Newton::correct(base::NonlinearProblem &problem,
                       Iterate                &it,
                       unsigned int            iteration,
                       double                  relative_residual,
                       double                  correction_tolerance,
                       const Observer         &observer) const
  {
    Vector<double> du = correction(problem, it.tangent, it.residual);
    // The energy slope along du; negative: du climbs the energy.
    const double slope = du * it.residual;
    it.climbs += slope < 0;
    if (slope < 0 && it.climbs >= parameters_.climbs_before_convex_tangent &&
        problem.use_convex_tangent())
      return; // same iterate, a tangent whose correction descends
    const double energy = std::abs(slope);
    if (it.first_energy == 0)
      it.first_energy = std::max(energy, 1e-300);
    const bool direction_small =
        correction_tolerance > 0 && du.linfty_norm() <= correction_tolerance;
    // The step filter comes first, so that the line search only tries
    // admissible (e.g. collision-free) configurations.
    const double fraction = problem.admissible_fraction(du);
    if (fraction < 1)
      du *= fraction;
    LineSearch search;
    if (parameters_.line_search)
    {
      // The first trial's tangent, as the next evaluation's.
      const bool trial_tangent =
          !direction_small && !it.prediction.expects_convergence(fraction == 1);
      search =
          search_line(problem, it, du, trial_tangent ? &it.tangent : nullptr);
      du *= search.scale;
    }
    it.corrections.add(search.scale <= smallest_line_search_scale, slope < 0);
    it.whole_correction = fraction == 1 && search.scale == 1;
    it.step_increment += du;
    it.correction_small =
        direction_small ||
        (energy <= parameters_.energy_tolerance * it.first_energy &&
         du.l2_norm() <= parameters_.increment_tolerance *
                             std::max(it.step_increment.l2_norm(), 1e-300));
    const bool next_with_tangent =
        !it.correction_small &&
        !it.prediction.expects_convergence(it.whole_correction);
    it.evaluated = apply_correction(problem, search, next_with_tangent, du,
                                    it.residual, it.trial_residual);
    if (!it.evaluated)
      it.energy = std::numeric_limits<double>::quiet_NaN();
    if (observer)
      observer({iteration, relative_residual, du.l2_norm(),
                energy / it.first_energy});
  }

  double Newton::single_correction(base::NonlinearProblem &problem,
                                   const Observer         &observer) const
  {
    problem.begin_solve();
    base::TangentMatrix &tangent = tangent_;
    problem.reinit_tangent(tangent);
    assemble_for_solver(problem, tangent);
    Vector<double> residual(problem.sparsity().n_rows());
    problem.evaluate(residual, &tangent);
    const double relative_residual =
        residual.l2_norm() / std::max(problem.force_scale(), 1e-300);
    if (!std::isfinite(relative_residual))
      throw NewtonFailure("non-finite residual");
    // Newton's rule (no step converges while a move is pending) holds
    // for the moves the correction cannot realize: accepted, such a step
    // would leave the obstacle behind its schedule, and a jammed one would
    // freeze the scene without a word. (The constrained unknowns' pending
    // increments are what this one correction carries out.)
    if (problem.prescribed_move_blocked())
      throw NewtonFailure("the linearized step failed: " + pending_move_note +
                          problem.failure_context());
    Vector<double> du       = correction(problem, tangent, residual);
    const double   fraction = problem.admissible_fraction(du);
    if (fraction < 1)
      du *= fraction;
    problem.apply_increment(du);
    problem.extrapolate_reports(du);
    if (observer)
      observer({0, relative_residual, du.l2_norm(), 1});
    return relative_residual;
  }

  StepController::StepController(const Settings &settings)
      : settings_(settings), size_(settings.initial)
  {
  }

  double StepController::size() const
  {
    return size_;
  }

  void StepController::success(unsigned int iterations)
  {
    cuts_ = 0;
    if (iterations <= settings_.easy_iterations)
      size_ = std::min(settings_.maximum, settings_.growth_factor * size_);
  }

  void StepController::failure(double             attempted,
                               const std::string &step,
                               const std::string &cause)
  {
    if (++cuts_ > settings_.max_consecutive_cuts)
      throw NewtonFailure(step + " failed after " +
                          std::to_string(settings_.max_consecutive_cuts) +
                          " step cuts: " + cause);
    size_ = settings_.cut_factor * attempted;
    if (size_ < settings_.minimum)
      throw NewtonFailure(step + " failed: the step size " +
                          short_number(size_) + " fell below its minimum " +
                          short_number(settings_.minimum) + ": " + cause);
  }
} // namespace coshell::solvers
