#include <coshell/solvers/time_integration.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

namespace coshell::solvers
{
  using namespace dealii;

  /// The rates of a scheme as functions of the step increment q (in the
  /// tangent space: translations, material rotation vectors).
  struct TimeIntegration::Scheme
  {
    bool   euler = false, linearized = false;
    double alpha_m = 0, alpha_f = 0, beta = 0.25, gamma = 0.5;
    double h = 0;
    /// Rates at the start of the step; a_n: generalized-alpha's
    /// pseudo-acceleration.
    Vector<double> v_n, vdot_n, a_n, a;

    Scheme(const std::string &method, double rho_inf)
        : euler(method != "generalized alpha"),
          linearized(method == "linearized implicit euler")
    {
      // Chung & Hulbert (1993) parameters from the spectral radius.
      alpha_m = (2 * rho_inf - 1) / (rho_inf + 1);
      alpha_f = rho_inf / (rho_inf + 1);
      gamma   = 0.5 + alpha_f - alpha_m;
      beta    = 0.25 * (gamma + 0.5) * (gamma + 0.5);
    }

    void start(double step, const Vector<double> &v, const Vector<double> &vdot)
    {
      h      = step;
      v_n    = v;
      vdot_n = vdot;
      if (a_n.size() != v.size())
        a_n = vdot; // a consistent start: pseudo = true acceleration
      a.reinit(v.size());
    }

    double acceleration_coefficient() const
    {
      return euler ? 1 / (h * h)
                   : (1 - alpha_m) / ((1 - alpha_f) * h * h * beta);
    }

    double velocity_coefficient() const
    {
      return euler ? 1 / h : gamma / (h * beta);
    }

    /// The step increment to start Newton from.
    void predictor(Vector<double> &q) const
    {
      if (linearized)
      {
        q = 0; // linearize about q_n, as Baraff & Witkin
        return;
      }
      q.equ(h, v_n);
      if (euler)
        return;
      // Predict vdot_{n+1} = vdot_n, i.e. this pseudo-acceleration.
      Vector<double> a_predicted(vdot_n);
      a_predicted.add(-alpha_m, a_n);
      a_predicted /= 1 - alpha_m;
      q.add(h * h * (0.5 - beta), a_n, h * h * beta, a_predicted);
    }

    void rates(const Vector<double> &q, Vector<double> &v, Vector<double> &vdot)
    {
      if (euler)
      {
        v.equ(1 / h, q);
        vdot = v;
        vdot -= v_n;
        vdot /= h;
        return;
      }
      a = q;
      a.add(-h, v_n, -h * h * (0.5 - beta), a_n);
      a /= h * h * beta;
      v = v_n;
      v.add(h * (1 - gamma), a_n, h * gamma, a);
      vdot.equ(1 - alpha_m, a);
      vdot.add(alpha_m, a_n, -alpha_f, vdot_n);
      vdot /= 1 - alpha_f;
    }

    void accept()
    {
      if (!euler)
        a_n = a;
    }
  };

  namespace
  {
    /// The nonlinear problem of one time step: moving the configuration
    /// moves the rates with it.
    class StepProblem : public base::NonlinearProblem
    {
    public:
      StepProblem(base::EvolutionProblem  &problem,
                  TimeIntegration::Scheme &scheme)
          : problem_(problem), scheme_(scheme)
      {
      }
      const SparsityPattern &sparsity() const override
      {
        return problem_.sparsity();
      }
      void begin_solve() override
      {
        problem_.begin_solve();
      }
      void reinit_tangent(base::TangentMatrix &K) const override
      {
        problem_.reinit_tangent(K);
      }
      void evaluate(Vector<double> &r, base::TangentMatrix *K) override
      {
        problem_.evaluate(r, K);
      }
      double energy() override
      {
        return problem_.energy();
      }
      double force_scale() const override
      {
        return problem_.force_scale();
      }
      bool prescribed_increment_pending() const override
      {
        return problem_.prescribed_increment_pending();
      }
      bool prescribed_move_blocked() const override
      {
        return problem_.prescribed_move_blocked();
      }
      void distribute(Vector<double> &x) const override
      {
        problem_.distribute(x);
      }
      void apply_increment(const Vector<double> &dx) override
      {
        problem_.apply_increment(dx);
        update_rates();
      }
      double admissible_fraction(const Vector<double> &dx) const override
      {
        return problem_.admissible_fraction(dx);
      }
      void extrapolate_reports(const Vector<double> &dx) override
      {
        problem_.extrapolate_reports(dx);
      }
      void save() override
      {
        problem_.save();
      }
      void restore() override
      {
        problem_.restore();
      }
      void begin_trial() override
      {
        problem_.begin_trial();
      }
      void end_trial() override
      {
        problem_.end_trial();
      }
      void keep_trial() override
      {
        problem_.keep_trial();
      }
      bool symmetric_tangent() const override
      {
        return problem_.symmetric_tangent();
      }
      bool use_convex_tangent() override
      {
        return problem_.use_convex_tangent();
      }
      std::string failure_context() const override
      {
        return problem_.failure_context();
      }
      void update_rates()
      {
        problem_.step_increment(q_);
        scheme_.rates(q_, problem_.velocity(), problem_.acceleration());
      }

    private:
      base::EvolutionProblem  &problem_;
      TimeIntegration::Scheme &scheme_;
      Vector<double>           q_;
    };

    /// Sets the predictor's increment q as the step's start. The predictor
    /// is a step like any other: the collision filter scales it. It
    /// certifies the straight path to the predicted position, so a scaled
    /// SE(3) step is set as a straight one.
    void set_filtered_prediction(base::EvolutionProblem &problem,
                                 const Vector<double>   &q,
                                 Vector<double>         &displacement)
    {
      problem.step_displacement(q, displacement);
      const double admissible = problem.admissible_fraction(displacement);
      if (admissible < 1)
      {
        displacement *= admissible;
        problem.set_step_displacement(displacement);
      }
      else
        problem.set_step_increment(q);
    }

    /// Starts the step of size h to 'time': the scheme's coefficients and
    /// its predictor, filtered, as the step's first increment.
    void start_step(base::EvolutionProblem  &problem,
                    TimeIntegration::Scheme &scheme,
                    double                   time,
                    double                   h,
                    Vector<double>          &q,
                    Vector<double>          &displacement)
    {
      scheme.start(h, problem.velocity(), problem.acceleration());
      problem.set_time(time);
      problem.set_rate_coefficients(scheme.acceleration_coefficient(),
                                    scheme.velocity_coefficient());
      scheme.predictor(q);
      set_filtered_prediction(problem, q, displacement);
    }

    /// Solves the step's nonlinear problem: one correction (linearized)
    /// or Newton, whose converged step 'check' may reject. Returns the
    /// iterations; throws NewtonFailure.
    unsigned int solve_step(const Newton                     &newton,
                            StepProblem                      &step_problem,
                            bool                              linearized,
                            const Newton::Observer           &observe,
                            const TimeIntegration::StepCheck &check,
                            TimeIntegration::StepRecord       record)
    {
      if (linearized)
      {
        newton.single_correction(step_problem, observe);
        return 1;
      }
      record.iterations = newton.solve(step_problem, observe, record.dt);
      // The linearized step evaluates no forces at its end, so its work
      // is unknown there: the guard judges Newton's steps only.
      if (check)
        if (const std::string reason = check(record); !reason.empty())
          throw NewtonFailure(reason);
      return record.iterations;
    }

    /// The log's progress line, at most every 'interval' s of wall time.
    class ProgressLog
    {
    public:
      ProgressLog(double interval, double simulated_start)
          : interval_(interval), simulated_start_(simulated_start)
      {
      }
      void after_step(std::ostream &log,
                      unsigned int  step,
                      double        t,
                      double        h,
                      unsigned int  iterations)
      {
        const auto now = std::chrono::steady_clock::now();
        if (std::chrono::duration<double>(now - last_).count() < interval_)
          return;
        const double wall =
            std::chrono::duration<double>(now - wall_start_).count();
        log << "  step " << step << ", t = " << t << " s, dt = " << h << " s, "
            << iterations << " iterations, real-time factor "
            << (t - simulated_start_) / std::max(wall, 1e-9) << '\n';
        last_ = now;
      }

    private:
      double interval_, simulated_start_;
      std::chrono::steady_clock::time_point
          wall_start_ = std::chrono::steady_clock::now(),
          last_       = wall_start_;
    };
  } // namespace

  void TimeIntegration::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Time integration");
    prm.declare_entry(
        "Method", "generalized alpha",
        Patterns::Selection(
            "generalized alpha|implicit euler|linearized implicit euler"),
        "generalized alpha: Lie-group generalized-alpha (second order, "
        "numerical damping of the high frequencies set by Spectral "
        "radius); implicit euler: backward Euler with full Newton (first "
        "order, strongly damped); linearized implicit euler: one linear "
        "solve per step (Baraff & Witkin 1998; SOFA and the seed paper), "
        "which reports the obstacles' forces at the step's end by their "
        "linearization (the force at the step's one evaluation plus its "
        "slopes times the correction).");
    prm.declare_entry(
        "Lie group", "R3xSO3", Patterns::Selection("R3xSO3|SE3"),
        "The group each vertex's configuration (x, R) is integrated on. "
        "R3xSO3: translations in global axes, "
        "rotations on SO(3). SE3: translation and rotation together, with "
        "velocities in the node's frame (Sonneville, Cardona & Bruls "
        "2014), so a motion of constant twist, such as a rigid spin, is "
        "integrated exactly at any step size, where R3xSO3 lags by the "
        "trapezoidal phase error (7 % at 30 degrees per step). SE3 needs "
        "Element/Formulation = corotational; its tangent is not symmetric.");
    prm.declare_entry("Time step", "1e-3", Patterns::Double(),
                      "Initial time step; > 0. Unit: time (s).");
    prm.declare_entry("Minimum time step", "1e-9", Patterns::Double(),
                      "The run stops with an error when a step must be cut "
                      "below this. Unit: time (s).");
    prm.declare_entry("Maximum time step", "1e-3", Patterns::Double(),
                      "Steps grow after easy ones up to this. Unit: time "
                      "(s).");
    prm.declare_entry("Spectral radius", "0.9", Patterns::Double(0, 1),
                      "rho_inf of generalized alpha, in [0, 1]: 1 keeps "
                      "every frequency (no numerical damping), 0 "
                      "annihilates the highest in one step. Unit: "
                      "dimensionless.");
    prm.declare_entry("End time", "1", Patterns::Double(),
                      "Duration of a scene with Analysis/Type = dynamic "
                      "and no stages (stages give their own Duration). "
                      "Unit: time (s).");
    prm.declare_entry("Maximum step cuts", "12", Patterns::Integer(0),
                      "How often in a row a failed step may be cut. Unit: "
                      "dimensionless (a count).");
    prm.declare_entry("Easy step iterations", "4", Patterns::Integer(1),
                      "A step converged in at most this many Newton "
                      "iterations lets the next grow. Unit: dimensionless "
                      "(a count).");
    prm.declare_entry("Step growth factor", "1.5", Patterns::Double(1),
                      "Growth of the time step after an easy step. Unit: "
                      "dimensionless.");
    prm.declare_entry("Step cut factor", "0.5", Patterns::Double(0.01, 0.99),
                      "A failed or rejected step is retried with the step "
                      "size times this. Unit: dimensionless.");
    prm.declare_entry(
        "Energy growth limit", "1", Patterns::Double(0),
        "Energy guard (0: off). A converged step is rejected and cut when "
        "the shell's energy (kinetic and strain) grows over it by more than "
        "the work done on the shell in the step (loads, supports' "
        "reactions, every contact force) plus this fraction of the larger "
        "of the energy at the step's start and that work. Catches Newton "
        "converging to a spurious state far from the step's start, which no "
        "residual test sees. The default 1 lets the energy double beyond "
        "the work: far above the trapezoidal rule's error in the step's "
        "work (up to half of the scale at a barrier's onset or under lagged "
        "friction), far below the spurious steps it exists for (energy "
        "times 80 and more). Costs one strain-energy pass per step. "
        "Newton's schemes only: a linearized step evaluates no forces at "
        "its end, and is not judged. Unit: dimensionless (a fraction of "
        "the energy).");
    prm.declare_entry("Progress interval", "5", Patterns::Double(0),
                      "Wall-clock time between progress lines (step, t, "
                      "dt, iterations, real-time factor); 0: every step. "
                      "Unit: s (wall clock).");
    prm.leave_subsection();
  }

  void TimeIntegration::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Time integration");
    method_              = prm.get("Method");
    se3_                 = prm.get("Lie group") == "SE3";
    time_step_           = prm.get_double("Time step");
    min_time_step_       = prm.get_double("Minimum time step");
    max_time_step_       = prm.get_double("Maximum time step");
    spectral_radius_     = prm.get_double("Spectral radius");
    end_time_            = prm.get_double("End time");
    max_step_cuts_       = prm.get_integer("Maximum step cuts");
    easy_iterations_     = prm.get_integer("Easy step iterations");
    growth_factor_       = prm.get_double("Step growth factor");
    cut_factor_          = prm.get_double("Step cut factor");
    progress_interval_   = prm.get_double("Progress interval");
    energy_growth_limit_ = prm.get_double("Energy growth limit");
    prm.leave_subsection();
    const std::string where = "Time integration/";
    if (!(time_step_ > 0))
      throw std::invalid_argument(where +
                                  "Time step = " + short_number(time_step_) +
                                  " must be positive");
    if (!(min_time_step_ > 0))
      throw std::invalid_argument(where + "Minimum time step must be positive");
    if (min_time_step_ > max_time_step_)
      throw std::invalid_argument(
          where + "Minimum time step = " + short_number(min_time_step_) +
          " exceeds Maximum time step = " + short_number(max_time_step_));
    if (!(end_time_ > 0))
      throw std::invalid_argument(where + "End time must be positive");
  }

  const std::string &TimeIntegration::method() const
  {
    return method_;
  }

  bool TimeIntegration::linearized() const
  {
    return method_ == "linearized implicit euler";
  }

  double TimeIntegration::energy_growth_limit() const
  {
    return energy_growth_limit_;
  }

  std::string TimeIntegration::known_risk() const
  {
    // Generalized alpha on R3xSO3 is not energy-stable for fast rotations
    // at large steps when it damps little (theory/dynamics.md, section
    // 18.7): only the guard then stops a step that creates energy.
    const bool little_damping = spectral_radius_ >= 0.9;
    if (method_ != "generalized alpha" || se3_ || !little_damping ||
        energy_growth_limit_ > 0)
      return {};
    return "warning: Time integration/Lie group = R3xSO3 with generalized "
           "alpha at Spectral radius = " +
           short_number(spectral_radius_) +
           " can gain energy in a step of a fast rotation, and Energy "
           "growth limit = 0 turns off the guard that rejects such a step";
  }

  bool TimeIntegration::se3() const
  {
    return se3_;
  }

  double TimeIntegration::end_time() const
  {
    return end_time_;
  }

  /// M vdot_0 = r(q_0, v_0, vdot = 0): the acceleration in equilibrium
  /// with the initial forces, which second-order accuracy needs.
  void TimeIntegration::initial_acceleration(base::EvolutionProblem &problem,
                                             LinearSolver &linear_solver) const
  {
    problem.acceleration() = 0;
    problem.set_rate_coefficients(0, 0);
    Vector<double>      residual(problem.sparsity().n_rows());
    base::TangentMatrix mass;
    problem.reinit_tangent(mass);
    problem.evaluate(residual, nullptr);
    problem.mass_matrix(mass);
    linear_solver.factorize(mass, true);
    Vector<double> acceleration(residual.size());
    linear_solver.solve(acceleration, residual);
    problem.distribute(acceleration);
    problem.acceleration() = acceleration;
  }

  double TimeIntegration::resumed_step_size(double        carried,
                                            std::ostream &log) const
  {
    // A restart may set other step limits than the run that wrote the
    // checkpoint; the carried size then obeys the limits in force.
    const double size = std::clamp(carried, min_time_step_, max_time_step_);
    if (size != carried)
      log << "  the carried time step " << carried
          << " s is clipped to Time integration/"
          << (size < carried ? "Maximum" : "Minimum") << " time step = " << size
          << " s\n";
    return size;
  }

  unsigned int TimeIntegration::run(base::EvolutionProblem  &problem,
                                    LinearSolver            &linear_solver,
                                    const NewtonParameters  &newton_parameters,
                                    double                   start,
                                    double                   end,
                                    unsigned int             first_step,
                                    const StepObserver      &on_step,
                                    const IterationObserver &on_iteration,
                                    std::ostream            &log,
                                    Carry                   *carry,
                                    const StepCheck         &step_check) const
  {
    const bool     resume = carry && carry->filled();
    Scheme         scheme(method_, spectral_radius_);
    StepProblem    step_problem(problem, scheme);
    const Newton   newton(newton_parameters, linear_solver);
    StepController control({resume ? resumed_step_size(carry->step_size, log)
                                   : std::min(time_step_, max_time_step_),
                            min_time_step_, max_time_step_, max_step_cuts_,
                            easy_iterations_, growth_factor_, cut_factor_});
    problem.set_time(start);
    if (resume)
      scheme.a_n = carry->pseudo_acceleration;
    else if (!scheme.euler)
      initial_acceleration(problem, linear_solver);
    problem.save();
    ProgressLog    progress(progress_interval_, start);
    double         t    = start;
    unsigned int   step = first_step;
    Vector<double> q(problem.sparsity().n_rows()), displacement;
    while (t < end - 1e-12 * std::max(1.0, std::abs(end)))
    {
      double h = std::min(control.size(), end - t);
      if (end - t - h < 0.01 * h) // no sliver of a last step
        h = end - t;
      start_step(problem, scheme, t + h, h, q, displacement);
      step_problem.update_rates();
      const auto observe = [&](const NewtonIteration &record)
      {
        if (on_iteration)
          on_iteration(step + 1, record);
      };
      try
      {
        const unsigned int iterations =
            solve_step(newton, step_problem, scheme.linearized, observe,
                       step_check, {step + 1, t + h, h, 0});
        scheme.accept();
        t += h;
        ++step;
        control.success(iterations);
        if (carry)
          *carry = {scheme.a_n, control.size()};
        // Before save(): the observer measures the step increment (work).
        on_step({step, t, h, iterations});
        problem.save();
        progress.after_step(log, step, t, h, iterations);
      }
      catch (const NewtonFailure &failure)
      {
        problem.restore();
        control.failure(h,
                        "time step from t = " + short_number(t) + " s to " +
                            short_number(t + h) + " s",
                        failure.what());
        log << "  time step to t = " << t + h << " s failed (" << failure.what()
            << "); cutting dt to " << control.size() << " s\n";
      }
    }
    return step - first_step;
  }
} // namespace coshell::solvers
