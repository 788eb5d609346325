#include <coshell/solvers/path_following.h>

#include <algorithm>
#include <cmath>

namespace coshell::solvers
{
  using namespace dealii;

  namespace
  {
    /// How load-control and arc-length steps start, grow and are cut.
    void declare_step_control_entries(ParameterHandler &prm)
    {
      prm.declare_entry("Load steps", "10", Patterns::Integer(1),
                        "Initial number of equal increments of the path "
                        "parameter from 0 to 1 (arc length: sets the first "
                        "arc from the first increment). Unit: dimensionless "
                        "(a count).");
      prm.declare_entry("Maximum step cuts", "12", Patterns::Integer(0),
                        "How often in a row a failed step may be cut before "
                        "the run stops with an error. Unit: dimensionless "
                        "(a count).");
      prm.declare_entry("Easy step iterations", "6", Patterns::Integer(1),
                        "A step that converged in at most this many Newton "
                        "iterations lets the next one grow. Unit: "
                        "dimensionless (a count).");
      prm.declare_entry("Step growth factor", "2", Patterns::Double(1),
                        "Growth of the step after an easy one, up to the "
                        "initial size. Unit: dimensionless.");
      prm.declare_entry("Step cut factor", "0.5", Patterns::Double(0.01, 0.99),
                        "A failed step is retried with this fraction of its "
                        "size. Unit: dimensionless.");
    }
  } // namespace

  void PathFollowing::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Nonlinear solver");
    prm.declare_entry("Method", "load control",
                      Patterns::Selection("load control|arc length"),
                      "load control: Newton-Raphson at prescribed values of "
                      "the path parameter (load factor, or stage time for "
                      "prescribed motions), cutting a failed step; arc "
                      "length: Crisfield's cylindrical arc-length method, "
                      "which follows limit points and snap-through (loads "
                      "only, no prescribed motions).");
    declare_step_control_entries(prm);
    NewtonParameters::declare_parameters(prm);
    prm.declare_entry("Maximum arc-length steps", "200", Patterns::Integer(1),
                      "Arc length: the run stops after this many steps "
                      "even if the load factor has not reached the "
                      "maximum. Unit: dimensionless (a count).");
    prm.declare_entry("Maximum load factor", "1", Patterns::Double(0),
                      "Arc length: stop once the load factor reaches "
                      "this. Unit: dimensionless.");
    prm.leave_subsection();
  }

  void PathFollowing::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Nonlinear solver");
    method_               = prm.get("Method");
    load_steps_           = prm.get_integer("Load steps");
    max_step_cuts_        = prm.get_integer("Maximum step cuts");
    easy_iterations_      = prm.get_integer("Easy step iterations");
    growth_factor_        = prm.get_double("Step growth factor");
    cut_factor_           = prm.get_double("Step cut factor");
    max_arc_length_steps_ = prm.get_integer("Maximum arc-length steps");
    max_load_factor_      = prm.get_double("Maximum load factor");
    newton_.parse_parameters(prm);
    prm.leave_subsection();
  }

  const std::string &PathFollowing::method() const
  {
    return method_;
  }

  bool PathFollowing::arc_length() const
  {
    return method_ == "arc length";
  }

  const NewtonParameters &PathFollowing::newton() const
  {
    return newton_;
  }

  /// Working data of one run.
  struct PathFollowing::Run
  {
    base::EvolutionProblem    &problem;
    LinearSolver              &linear_solver;
    const std::vector<double> &stops;
    const StepObserver        &on_step;
    const IterationObserver   &on_iteration;
    std::ostream              &log;
    unsigned int               step      = 0;
    double                     parameter = 0;
    Vector<double>             previous_step;

    Newton::Observer iteration_observer()
    {
      return [this](const NewtonIteration &record)
      {
        if (on_iteration)
          on_iteration(step + 1, record);
      };
    }

    /// Solves tangent * x = b with the last factorization, distributed.
    Vector<double> solve(const Vector<double> &b)
    {
      Vector<double> x(b.size());
      linear_solver.solve(x, b);
      problem.distribute(x);
      return x;
    }

    void converged(double new_parameter, unsigned int iterations)
    {
      parameter = new_parameter;
      ++step;
      // Before save(), as in time integration: observers may read what
      // the step did (the smallest contact gap over its iterates).
      on_step(step, parameter, iterations);
      problem.save();
    }
  };

  /// Steps of 1/(Load steps), never stepping over a stop, cutting a step
  /// that fails and growing it again after easy steps.
  void PathFollowing::parameter_control(Run &run) const
  {
    const double   initial = 1.0 / load_steps_;
    StepController control({initial, 1e-9, initial, max_step_cuts_,
                            easy_iterations_, growth_factor_, cut_factor_});
    const Newton   newton(newton_, run.linear_solver);
    while (run.parameter < 1 - 1e-12)
    {
      double target = std::min(1.0, run.parameter + control.size());
      for (const double stop : run.stops)
        if (stop > run.parameter + 1e-12 && stop < target - 1e-12)
          target = stop;
      try
      {
        run.problem.set_path_parameter(target);
        const unsigned int iterations =
            newton.solve(run.problem, run.iteration_observer());
        run.converged(target, iterations);
        control.success(iterations);
      }
      catch (const NewtonFailure &failure)
      {
        run.problem.restore();
        control.failure(
            target - run.parameter,
            "load step from load factor " + short_number(run.parameter) +
                " to " + short_number(target),
            std::string(failure.what()) + " (see newton_history.csv)");
        run.log << "  step to load factor " << target << " failed ("
                << failure.what() << "); cutting the increment to "
                << control.size() << '\n';
      }
    }
  }

  namespace
  {
    /// The load increment dl with |base + dl * from_load| = arc whose step
    /// is closest in direction to the current 'step' (of the two roots);
    /// throws NewtonFailure when there is no real root.
    double closest_arc_root(const Vector<double> &base,
                            const Vector<double> &from_load,
                            const Vector<double> &step,
                            double                arc)
    {
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
      return best_dl;
    }
  } // namespace

  /// One arc-length step of radius 'arc' (Crisfield 1981, cylindrical:
  /// |du_step| = arc, the parameter free). The predictor follows the
  /// tangent in the direction of the previous step; each corrector solves
  /// for the residual and the load direction with one factorization and
  /// picks the root of the constraint closest to the previous direction.
  /// Returns the iterations; throws NewtonFailure.
  unsigned int PathFollowing::arc_length_step(Run &run, double arc) const
  {
    base::EvolutionProblem &problem = run.problem;
    base::TangentMatrix     tangent;
    problem.reinit_tangent(tangent);
    Vector<double> residual(problem.sparsity().n_rows()), load;
    problem.set_path_parameter(run.parameter);
    problem.path_direction(load);
    problem.evaluate(residual, &tangent);
    run.linear_solver.factorize(tangent, problem.symmetric_tangent());
    const Vector<double> tangent_direction = run.solve(load);
    const double         sign              = run.previous_step.size() > 0 &&
                                tangent_direction * run.previous_step < 0
                                                 ? -1.0
                                                 : 1.0;
    double factor = run.parameter + sign * arc / tangent_direction.l2_norm();
    Vector<double> step = tangent_direction;
    step *= sign * arc / tangent_direction.l2_norm();
    problem.apply_increment(step);
    for (unsigned int iteration = 1;; ++iteration)
    {
      problem.set_path_parameter(factor);
      problem.path_direction(load);
      problem.evaluate(residual, &tangent);
      const double relative_residual =
          residual.l2_norm() / std::max(problem.force_scale(), 1e-300);
      if (run.on_iteration)
        run.on_iteration(run.step + 1, {iteration, relative_residual, 0, 0});
      if (!std::isfinite(relative_residual) ||
          relative_residual > newton_.divergence_limit)
        throw NewtonFailure("arc-length corrector diverged");
      if (relative_residual <= newton_.residual_tolerance)
      {
        run.previous_step = step;
        run.converged(factor, iteration);
        return iteration;
      }
      if (iteration == newton_.max_iterations)
        throw NewtonFailure("arc-length corrector did not converge in " +
                            std::to_string(newton_.max_iterations) +
                            " iterations");
      run.linear_solver.factorize(tangent, problem.symmetric_tangent());
      const Vector<double> from_residual = run.solve(residual);
      const Vector<double> from_load     = run.solve(load);
      Vector<double>       base          = step;
      base += from_residual;
      const double   best_dl    = closest_arc_root(base, from_load, step, arc);
      Vector<double> correction = from_residual;
      correction.add(best_dl, from_load);
      problem.apply_increment(correction);
      step += correction;
      factor += best_dl;
    }
  }

  /// Arc length: the first arc comes from the first load increment; an
  /// arc that fails is cut, an easy one grows by half (up to 4 times the
  /// first).
  void PathFollowing::arc_length_path(Run &run) const
  {
    base::TangentMatrix tangent;
    run.problem.reinit_tangent(tangent);
    Vector<double> residual(run.problem.sparsity().n_rows()), load;
    run.problem.set_path_parameter(0);
    run.problem.path_direction(load);
    run.problem.evaluate(residual, &tangent);
    run.linear_solver.factorize(tangent, run.problem.symmetric_tangent());
    const double first_arc = run.solve(load).l2_norm() / load_steps_;
    // The arc grows more cautiously than a load step (past a limit point
    // the path turns) and at most to four first arcs.
    constexpr double       largest_arc_in_first_arcs = 4;
    constexpr unsigned int arc_easy_iterations       = 4;
    constexpr double       arc_growth_factor         = 1.5;
    StepController control({first_arc, 0, largest_arc_in_first_arcs * first_arc,
                            max_step_cuts_, arc_easy_iterations,
                            arc_growth_factor, cut_factor_});
    while (run.parameter < max_load_factor_ - 1e-12 &&
           run.step < max_arc_length_steps_)
    {
      try
      {
        control.success(arc_length_step(run, control.size()));
      }
      catch (const NewtonFailure &failure)
      {
        run.problem.restore();
        control.failure(control.size(),
                        "arc-length step at load factor " +
                            short_number(run.parameter),
                        failure.what());
        run.log << "  arc-length step failed (" << failure.what()
                << "); arc cut to " << control.size() << '\n';
      }
    }
  }

  void PathFollowing::run(base::EvolutionProblem    &problem,
                          LinearSolver              &linear_solver,
                          const std::vector<double> &stops,
                          const StepObserver        &on_step,
                          const IterationObserver   &on_iteration,
                          std::ostream              &log) const
  {
    Run run{problem, linear_solver, stops, on_step, on_iteration, log, 0, 0,
            {}};
    problem.save();
    if (arc_length())
      arc_length_path(run);
    else
      parameter_control(run);
  }
} // namespace coshell::solvers
