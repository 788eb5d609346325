#include <coshell/solvers/nonlinear_static.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace coshell::solvers
{
  using namespace dealii;

  void NonlinearStatic::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Nonlinear solver");
    prm.declare_entry("Method", "load control",
                      Patterns::Selection("load control|arc length"),
                      "load control: Newton-Raphson at prescribed load "
                      "factors, cutting a failed step in half; arc length: "
                      "Crisfield's cylindrical arc-length method, which "
                      "follows limit points and snap-through.");
    prm.declare_entry("Tangent", "consistent",
                      Patterns::Selection("consistent|paper"),
                      "consistent: exact derivative of the co-rotational "
                      "internal force (quadratic convergence); paper: the "
                      "approximation R K R^T of Comas et al. 2010.");
    prm.declare_entry("Load steps", "10", Patterns::Integer(1),
                      "Initial number of equal load increments from 0 to 1 "
                      "(arc length: sets the first arc from the first "
                      "increment).");
    prm.declare_entry("Maximum step cuts", "12", Patterns::Integer(0),
                      "How often a failed step may be halved before the "
                      "run stops with an error.");
    prm.declare_entry("Maximum iterations", "30", Patterns::Integer(1),
                      "Newton iterations per attempt of a step.");
    prm.declare_entry("Residual tolerance", "1e-7", Patterns::Double(0),
                      "Newton has converged when |r| <= tol |load|, or when "
                      "both Energy and Increment tolerances are met.");
    prm.declare_entry("Energy tolerance", "1e-16", Patterns::Double(0),
                      "|du.r| <= tol |du_0.r_0|: the energy of the last "
                      "correction relative to the first of the step.");
    prm.declare_entry("Increment tolerance", "1e-8", Patterns::Double(0),
                      "|du| <= tol |sum of corrections in the step|.");
    prm.declare_entry("Line search", "false", Patterns::Bool(),
                      "Scale each Newton correction du by s so that "
                      "|du.r(s du)| <= 0.8 |du.r(0)| (secant steps on the "
                      "energy slope, Crisfield 1991). Off by default: on "
                      "large-rotation steps the full Newton step, though it "
                      "raises the residual at first, converges faster.");
    prm.declare_entry("Maximum arc-length steps", "200", Patterns::Integer(1),
                      "Arc length: the run stops after this many steps "
                      "even if the load factor has not reached the maximum.");
    prm.declare_entry("Maximum load factor", "1", Patterns::Double(0),
                      "Arc length: stop once the load factor reaches this.");
    prm.leave_subsection();
  }

  void NonlinearStatic::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Nonlinear solver");
    method_               = prm.get("Method");
    tangent_              = prm.get("Tangent") == "paper"
                                ? element::CorotationalTangent::paper
                                : element::CorotationalTangent::consistent;
    load_steps_           = prm.get_integer("Load steps");
    max_step_cuts_        = prm.get_integer("Maximum step cuts");
    max_iterations_       = prm.get_integer("Maximum iterations");
    residual_tolerance_   = prm.get_double("Residual tolerance");
    energy_tolerance_     = prm.get_double("Energy tolerance");
    increment_tolerance_  = prm.get_double("Increment tolerance");
    line_search_          = prm.get_bool("Line search");
    max_arc_length_steps_ = prm.get_integer("Maximum arc-length steps");
    max_load_factor_      = prm.get_double("Maximum load factor");
    prm.leave_subsection();
  }

  element::CorotationalTangent NonlinearStatic::tangent() const
  {
    return tangent_;
  }

  const std::string &NonlinearStatic::method() const
  {
    return method_;
  }

  /// Working data of one run.
  struct NonlinearStatic::Context
  {
    const model::CorotationalModel  &model;
    model::ShellState               &state;
    const LoadPattern               &loads;
    const AffineConstraints<double> &constraints;
    LinearSolver                    &linear_solver;
    const std::vector<double>       &stop_factors;
    const StepObserver              &observer;
    std::ostream                    &log;
    std::ostream                    &history;
    element::CorotationalTangent     tangent_type;
    SparseMatrix<double>             tangent;
    Vector<double>                   residual;
    unsigned int                     step        = 0;
    double                           load_factor = 0;
    Vector<double>                   previous_step;

    void assemble(const model::ShellState &at, double factor, bool with_tangent)
    {
      model.assemble(at, factor, loads.dead_load, loads.follower_pressure,
                     tangent_type, constraints, residual,
                     with_tangent ? &tangent : nullptr);
    }

    /// Condensed external load direction at the current configuration.
    Vector<double> load_direction() const
    {
      Vector<double> load(residual.size());
      model.load_vector(state, loads.dead_load, loads.follower_pressure, load);
      constraints.condense(load);
      return load;
    }

    /// Solves tangent * x = b (the tangent must be factorized first).
    Vector<double> solve(const Vector<double> &b)
    {
      Vector<double> x(b.size());
      linear_solver.solve(x, b);
      constraints.distribute(x);
      return x;
    }

    void record(unsigned int iteration,
                double       factor,
                double       relative_residual,
                double       increment_norm,
                double       energy)
    {
      history << step + 1 << ',' << iteration << ',' << std::setprecision(12)
              << factor << ',' << relative_residual << ',' << increment_norm
              << ',' << energy << '\n';
    }
  };

  namespace
  {
    std::string number(double x)
    {
      std::ostringstream out;
      out << std::setprecision(6) << x;
      return out.str();
    }

    bool is_finite(const Vector<double> &v)
    {
      return std::all_of(v.begin(), v.end(),
                         [](double x) { return std::isfinite(x); });
    }
  } // namespace

  /// Crisfield's line search on the energy slope s(a) = du . r(u + a du):
  /// accept a when |s(a)| <= 0.8 |s(0)|, else take secant steps towards
  /// s = 0, keeping a in [0.1, 1].
  double NonlinearStatic::line_search_scale(
      Context &c, double load_factor, const Vector<double> &correction) const
  {
    const double slope_at_zero = correction * c.residual;
    double       a_low = 0, s_low = slope_at_zero, a = 1;
    for (unsigned int trial = 0; trial < 4; ++trial)
    {
      model::ShellState trial_state = c.state;
      Vector<double>    step        = correction;
      step *= a;
      trial_state.apply_increment(step);
      c.assemble(trial_state, load_factor, false);
      const double slope = correction * c.residual;
      if (!std::isfinite(slope))
      {
        a = 0.5 * (a_low + a);
        continue;
      }
      if (std::abs(slope) <= 0.8 * std::abs(slope_at_zero))
        return a;
      const double secant = a_low + (a - a_low) * s_low / (s_low - slope);
      a_low               = a;
      s_low               = slope;
      a = std::clamp(std::isfinite(secant) ? secant : 1.0, 0.1, 1.0);
    }
    return a;
  }

  /// Newton iterations at a fixed load factor. Returns the number of
  /// iterations; throws NewtonFailure (leaving 'state' wherever it got).
  unsigned int NonlinearStatic::newton(Context &c, double load_factor) const
  {
    const double load_norm =
        std::max(std::abs(load_factor) * c.load_direction().l2_norm(), 1e-300);
    Vector<double> step_increment(c.residual.size());
    double         first_energy     = 0;
    bool           correction_small = false;
    for (unsigned int iteration = 0;; ++iteration)
    {
      c.assemble(c.state, load_factor, true);
      const double relative_residual = c.residual.l2_norm() / load_norm;
      if (!std::isfinite(relative_residual) || relative_residual > 1e8)
        throw NewtonFailure("Newton diverged (relative residual " +
                            number(relative_residual) + ")");
      // Converged when the residual is small, or when the last correction
      // has dropped to round-off in both norm and energy: very stiff
      // membranes leave a round-off floor in the residual.
      if (relative_residual <= residual_tolerance_ || correction_small)
      {
        c.record(iteration, load_factor, relative_residual, 0, 0);
        return iteration;
      }
      if (iteration == max_iterations_)
        throw NewtonFailure("Newton did not converge in " +
                            std::to_string(max_iterations_) +
                            " iterations (relative residual " +
                            number(relative_residual) + ")");
      c.linear_solver.factorize(c.tangent, false);
      Vector<double> correction = c.solve(c.residual);
      const double   energy     = std::abs(correction * c.residual);
      if (iteration == 0)
        first_energy = std::max(energy, 1e-300);
      if (line_search_)
        correction *= line_search_scale(c, load_factor, correction);
      if (!is_finite(correction))
        throw NewtonFailure("the linear solve gave non-finite values");
      c.state.apply_increment(correction);
      step_increment += correction;
      c.record(iteration, load_factor, relative_residual, correction.l2_norm(),
               energy / first_energy);
      correction_small =
          energy <= energy_tolerance_ * first_energy &&
          correction.l2_norm() <=
              increment_tolerance_ * std::max(step_increment.l2_norm(), 1e-300);
    }
  }

  /// Load control: steps of 1/(Load steps), never stepping over a stop
  /// factor, halving a step that fails and growing it again after easy
  /// steps.
  void NonlinearStatic::load_control(Context &c) const
  {
    const double initial_increment = 1.0 / load_steps_;
    double       increment         = initial_increment;
    unsigned int cuts              = 0;
    while (c.load_factor < 1 - 1e-12)
    {
      double target = std::min(1.0, c.load_factor + increment);
      for (const double stop : c.stop_factors)
        if (stop > c.load_factor + 1e-12 && stop < target - 1e-12)
          target = stop;
      try
      {
        const unsigned int iterations = newton(c, target);
        c.state.save();
        c.load_factor = target;
        ++c.step;
        c.observer(c.step, c.load_factor, iterations, c.state);
        cuts = 0;
        if (iterations <= 6)
          increment = std::min(initial_increment, 2 * increment);
      }
      catch (const NewtonFailure &failure)
      {
        c.state.restore();
        if (++cuts > max_step_cuts_)
          throw NewtonFailure(
              "load step from load factor " + number(c.load_factor) + " to " +
              number(target) + " failed after " +
              std::to_string(max_step_cuts_) + " step cuts: " + failure.what() +
              " (see newton_history.csv)");
        increment = 0.5 * (target - c.load_factor);
        if (increment < 1e-9)
          throw NewtonFailure("the load increment fell below 1e-9 at load "
                              "factor " +
                              number(c.load_factor) + ": " + failure.what() +
                              " (see newton_history.csv)");
        c.log << "  step to load factor " << target << " failed ("
              << failure.what() << "); cutting the increment to " << increment
              << '\n';
      }
    }
  }

  /// One arc-length step of radius 'arc' (Crisfield 1981, cylindrical:
  /// |du_step| = arc, the load factor free). The predictor follows the
  /// tangent in the direction of the previous step; each corrector solves
  /// for the residual and the load direction with one factorization and
  /// picks the root of the constraint closest to the previous direction.
  /// Returns the iterations; throws NewtonFailure.
  unsigned int NonlinearStatic::arc_length_step(Context &c, double arc) const
  {
    Vector<double> load = c.load_direction();
    c.assemble(c.state, c.load_factor, true);
    c.linear_solver.factorize(c.tangent, false);
    const Vector<double> tangent_direction = c.solve(load);
    const double         sign =
        c.previous_step.size() > 0 && tangent_direction * c.previous_step < 0
                    ? -1.0
                    : 1.0;
    double factor = c.load_factor + sign * arc / tangent_direction.l2_norm();
    Vector<double> step = tangent_direction;
    step *= sign * arc / tangent_direction.l2_norm();
    c.state.apply_increment(step);
    for (unsigned int iteration = 1;; ++iteration)
    {
      load = c.load_direction();
      c.assemble(c.state, factor, true);
      const double relative_residual =
          c.residual.l2_norm() /
          std::max(std::abs(factor) * load.l2_norm(), 1e-300);
      c.record(iteration, factor, relative_residual, 0, 0);
      if (!std::isfinite(relative_residual) || relative_residual > 1e8)
        throw NewtonFailure("arc-length corrector diverged");
      if (relative_residual <= residual_tolerance_)
      {
        c.load_factor   = factor;
        c.previous_step = step;
        return iteration;
      }
      if (iteration == max_iterations_)
        throw NewtonFailure("arc-length corrector did not converge in " +
                            std::to_string(max_iterations_) + " iterations");
      c.linear_solver.factorize(c.tangent, false);
      const Vector<double> from_residual = c.solve(c.residual);
      const Vector<double> from_load     = c.solve(load);
      Vector<double>       base          = step;
      base += from_residual;
      // |base + dl * from_load|^2 = arc^2
      const double a = from_load * from_load, b = 2 * (from_load * base),
                   q            = base * base - arc * arc;
      const double discriminant = b * b - 4 * a * q;
      if (discriminant < 0)
        throw NewtonFailure("arc-length constraint has no real root");
      double best_dl = 0, best_alignment = -1e300;
      for (const double root : {(-b + std::sqrt(discriminant)) / (2 * a),
                                (-b - std::sqrt(discriminant)) / (2 * a)})
      {
        Vector<double> candidate = base;
        candidate.add(root, from_load);
        if (candidate * step > best_alignment)
        {
          best_alignment = candidate * step;
          best_dl        = root;
        }
      }
      Vector<double> correction = from_residual;
      correction.add(best_dl, from_load);
      c.state.apply_increment(correction);
      step += correction;
      factor += best_dl;
    }
  }

  /// Arc length: the first arc comes from the first load increment; an
  /// arc that fails is halved, an easy one grows by half (up to 4 times
  /// the first).
  void NonlinearStatic::arc_length(Context &c) const
  {
    c.assemble(c.state, 0, true);
    c.linear_solver.factorize(c.tangent, false);
    const double first_arc =
        c.solve(c.load_direction()).l2_norm() / load_steps_;
    double       arc  = first_arc;
    unsigned int cuts = 0;
    while (c.load_factor < max_load_factor_ - 1e-12 &&
           c.step < max_arc_length_steps_)
    {
      try
      {
        const unsigned int iterations = arc_length_step(c, arc);
        c.state.save();
        ++c.step;
        c.observer(c.step, c.load_factor, iterations, c.state);
        cuts = 0;
        if (iterations <= 4)
          arc = std::min(4 * first_arc, 1.5 * arc);
      }
      catch (const NewtonFailure &failure)
      {
        c.state.restore();
        if (++cuts > max_step_cuts_)
          throw NewtonFailure("arc-length step at load factor " +
                              number(c.load_factor) + " failed after " +
                              std::to_string(max_step_cuts_) +
                              " cuts: " + failure.what());
        arc *= 0.5;
        c.log << "  arc-length step failed (" << failure.what()
              << "); arc cut to " << arc << '\n';
      }
    }
  }

  void NonlinearStatic::run(const model::CorotationalModel  &model,
                            model::ShellState               &state,
                            const LoadPattern               &loads,
                            const AffineConstraints<double> &constraints,
                            const SparsityPattern           &sparsity,
                            LinearSolver                    &linear_solver,
                            const std::vector<double>       &stop_factors,
                            const StepObserver              &observer,
                            std::ostream                    &log,
                            std::ostream                    &history) const
  {
    Context c{model,
              state,
              loads,
              constraints,
              linear_solver,
              stop_factors,
              observer,
              log,
              history,
              tangent_,
              SparseMatrix<double>(sparsity),
              Vector<double>(state.values().size()),
              0,
              0.0,
              Vector<double>()};
    history << "step,iteration,load_factor,relative_residual,"
               "correction_norm,relative_energy\n";
    state.save();
    if (method_ == "arc length")
      arc_length(c);
    else
      load_control(c);
  }
} // namespace coshell::solvers
