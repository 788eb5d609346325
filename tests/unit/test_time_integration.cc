// The time integrators (solvers::TimeIntegration) on small linear
// mass-spring systems written here, against what is known of the schemes
// without running them: the trapezoidal rule (generalized alpha at
// rho_inf = 1) conserves the energy of a linear oscillator exactly;
// backward Euler divides it by 1 + (omega h)^2 each step; generalized alpha
// is second order and backward Euler first; generalized alpha's spectral
// radius tends to rho_inf as omega h grows (Chung & Hulbert 1993); on a
// linear problem one Newton correction (the linearized scheme) is the
// converged step; a run continued from its Carry is the uninterrupted run.

#include <coshell/solvers/time_integration.h>

#include "solver_test_utilities.h"

#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/lapack_full_matrix.h>

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace
{
  using coshell::solvers::testing::umfpack;
  using namespace dealii;
  using coshell::base::EvolutionProblem;
  using coshell::base::TangentMatrix;
  using coshell::solvers::LinearSolver;
  using coshell::solvers::NewtonFailure;
  using coshell::solvers::NewtonParameters;
  using coshell::solvers::TimeIntegration;

  /// M xdd + C xd + K x = f(t) on a few DoFs, in the form the integrators
  /// see: r = f(t) - K x - C v - M a, tangent K + c_a M + c_v C. The rates
  /// are the integrator's (velocity(), acceleration()); save() and
  /// restore() keep them with the configuration, as ShellState does.
  class MassSpring : public EvolutionProblem
  {
  public:
    MassSpring(const FullMatrix<double> &M,
               const FullMatrix<double> &K,
               const FullMatrix<double> &C = FullMatrix<double>())
        : M_(M), K_(K), C_(C.m() ? C : FullMatrix<double>(M.m(), M.n())),
          x_(M.m()), v_(M.m()), a_(M.m())
    {
      DynamicSparsityPattern dsp(M.m(), M.m());
      for (unsigned int i = 0; i < M.m(); ++i)
        for (unsigned int j = 0; j < M.m(); ++j)
          dsp.add(i, j);
      pattern_.copy_from(dsp);
      save();
    }

    /// f(t); none by default.
    std::function<void(double, Vector<double> &)> load;
    /// Evaluations whose step (time since save()) is longer than this give
    /// a non-finite residual: a forced Newton failure.
    double longest_step = 1e300;

    const SparsityPattern &sparsity() const override
    {
      return pattern_;
    }

    void evaluate(Vector<double> &r, TangentMatrix *tangent) override
    {
      Vector<double> f(size()), Kx(size()), Cv(size()), Ma(size());
      if (load)
        load(time_, f);
      K_.vmult(Kx, x_);
      C_.vmult(Cv, v_);
      M_.vmult(Ma, a_);
      r = f;
      r -= Kx;
      r -= Cv;
      r -= Ma;
      scale_ = std::max(
          {f.l2_norm(), Kx.l2_norm(), Cv.l2_norm(), Ma.l2_norm(), 1e-300});
      if (time_ - saved_time_ > longest_step)
        r[0] = std::numeric_limits<double>::quiet_NaN();
      if (tangent)
        for (unsigned int i = 0; i < size(); ++i)
          for (unsigned int j = 0; j < size(); ++j)
            tangent->serial().set(i, j,
                                  K_(i, j) + ac_ * M_(i, j) + vc_ * C_(i, j));
    }

    double force_scale() const override
    {
      return scale_;
    }
    void distribute(Vector<double> &) const override {}
    void apply_increment(const Vector<double> &dx) override
    {
      x_ += dx;
    }
    void save() override
    {
      saved_x_    = x_;
      saved_v_    = v_;
      saved_a_    = a_;
      saved_time_ = time_;
    }
    void restore() override
    {
      x_ = saved_x_;
      v_ = saved_v_;
      a_ = saved_a_;
    }
    bool symmetric_tangent() const override
    {
      return true;
    }

    void set_path_parameter(double) override {}
    void path_direction(Vector<double> &direction) override
    {
      direction.reinit(size());
    }
    void set_time(double time) override
    {
      time_ = time;
    }
    void step_increment(Vector<double> &q) const override
    {
      q = x_;
      q -= saved_x_;
    }
    void set_step_increment(const Vector<double> &q) override
    {
      x_ = saved_x_;
      x_ += q;
    }
    Vector<double> &velocity() override
    {
      return v_;
    }
    Vector<double> &acceleration() override
    {
      return a_;
    }
    void set_rate_coefficients(double acceleration_coefficient,
                               double velocity_coefficient) override
    {
      ac_ = acceleration_coefficient;
      vc_ = velocity_coefficient;
    }
    void mass_matrix(TangentMatrix &mass) override
    {
      for (unsigned int i = 0; i < size(); ++i)
        for (unsigned int j = 0; j < size(); ++j)
          mass.serial().set(i, j, M_(i, j));
    }

    Vector<double> &x()
    {
      return x_;
    }
    /// 1/2 v.M v + 1/2 x.K x.
    double mechanical_energy() const
    {
      return 0.5 * M_.matrix_norm_square(v_) + 0.5 * K_.matrix_norm_square(x_);
    }

  private:
    unsigned int size() const
    {
      return M_.m();
    }
    FullMatrix<double> M_, K_, C_;
    Vector<double>     x_, v_, a_, saved_x_, saved_v_, saved_a_;
    SparsityPattern    pattern_;
    double             time_ = 0, saved_time_ = 0, ac_ = 0, vc_ = 0, scale_ = 0;
  };

  FullMatrix<double> matrix(unsigned int                        n,
                            const std::initializer_list<double> entries)
  {
    FullMatrix<double> m(n, n);
    m.fill(entries.begin());
    return m;
  }

  /// One DoF: m = 1, k = omega^2.
  MassSpring oscillator(double omega)
  {
    return MassSpring(matrix(1, {1.0}), matrix(1, {omega * omega}));
  }

  std::string text(double x)
  {
    std::ostringstream out;
    out.precision(17);
    out << x;
    return out.str();
  }

  /// A scheme at a fixed step h (no growth, no cuts unless 'minimum').
  TimeIntegration integrator(const std::string &method,
                             double             h,
                             double             rho_inf = 0.9,
                             double             minimum = 1e-12)
  {
    ParameterHandler prm;
    TimeIntegration::declare_parameters(prm);
    prm.enter_subsection("Time integration");
    prm.set("Method", method);
    prm.set("Time step", text(h));
    prm.set("Maximum time step", text(h));
    prm.set("Minimum time step", text(minimum));
    prm.set("Spectral radius", text(rho_inf));
    prm.set("Progress interval", "1e9");
    prm.leave_subsection();
    TimeIntegration scheme;
    scheme.parse_parameters(prm);
    return scheme;
  }

  /// Linear problems: converge to round-off, not to Newton's default 1e-7.
  /// A step's residual has a round-off floor of about eps / (omega h)^2
  /// (the increment's round-off, divided by h^2 in the acceleration),
  /// 1e-12 at omega h = 0.01: the tolerance stays above it.
  NewtonParameters tight()
  {
    NewtonParameters parameters;
    parameters.residual_tolerance = 1e-10;
    return parameters;
  }

  /// Runs 'scheme' on 'problem' from 'start' to 'end', calling 'on_step'.
  unsigned int run(const TimeIntegration               &scheme,
                   MassSpring                          &problem,
                   double                               start,
                   double                               end,
                   const TimeIntegration::StepObserver &on_step = {},
                   TimeIntegration::Carry              *carry   = nullptr)
  {
    std::ostringstream log;
    return scheme.run(problem, umfpack(), tight(), start, end, 0,
                      on_step ? on_step
                              : TimeIntegration::StepObserver(
                                    [](const TimeIntegration::StepRecord &) {}),
                      {}, log, carry);
  }

  /// |error| of x and v / omega at t = 1 against x = cos(omega t) for the
  /// oscillator started at x = 1, v = 0, in 'steps' steps.
  double
  error_at_one(const std::string &method, unsigned int steps, double rho_inf)
  {
    const double omega   = 2 * M_PI;
    MassSpring   problem = oscillator(omega);
    problem.x()[0]       = 1;
    problem.save();
    EXPECT_EQ(run(integrator(method, 1.0 / steps, rho_inf), problem, 0, 1),
              steps);
    return std::hypot(problem.x()[0] - std::cos(omega),
                      (problem.velocity()[0] + omega * std::sin(omega)) /
                          omega);
  }

  /// The amplification matrix of one generalized-alpha step of size h on
  /// x'' + omega^2 x = 0, column by column: the step taken from the unit
  /// states (x, v, a) = e_k (a: the pseudo-acceleration, set through the
  /// Carry, the true acceleration -omega^2 x in equilibrium). Returns its
  /// spectral radius.
  double spectral_radius(double omega_h, double rho_inf)
  {
    const double          h = 1e-2, omega = omega_h / h;
    const TimeIntegration scheme = integrator("generalized alpha", h, rho_inf);
    LAPACKFullMatrix<double> amplification(3, 3);
    for (unsigned int k = 0; k < 3; ++k)
    {
      MassSpring problem        = oscillator(omega);
      problem.x()[0]            = k == 0;
      problem.velocity()[0]     = k == 1;
      problem.acceleration()[0] = -omega * omega * problem.x()[0];
      problem.save();
      TimeIntegration::Carry carry;
      carry.pseudo_acceleration.reinit(1);
      carry.pseudo_acceleration[0] = k == 2;
      carry.step_size              = h;
      EXPECT_EQ(run(scheme, problem, 0, h, {}, &carry), 1u);
      amplification(0, k) = problem.x()[0];
      amplification(1, k) = problem.velocity()[0];
      amplification(2, k) = carry.pseudo_acceleration[0];
    }
    amplification.compute_eigenvalues();
    double radius = 0;
    for (unsigned int k = 0; k < 3; ++k)
      radius = std::max(radius, std::abs(amplification.eigenvalue(k)));
    return radius;
  }
} // namespace

// Generalized alpha at rho_inf = 1 is Newmark's average acceleration (the
// trapezoidal rule): on an undamped linear system it conserves
// 1/2 v.M v + 1/2 x.K x exactly, at any step size, so each step changes
// it by round-off only. Two coupled DoFs, 200 steps of about a tenth of
// the shorter period.
TEST(TimeIntegration, GeneralizedAlphaAtRhoOneConservesTheEnergy)
{
  MassSpring problem(matrix(2, {1.0, 0.0, 0.0, 2.0}),
                     matrix(2, {30.0, -10.0, -10.0, 20.0}));
  problem.x()[0]        = 1;
  problem.velocity()[1] = 0.5;
  problem.save();
  const double initial = problem.mechanical_energy();
  double       largest = 0;
  EXPECT_EQ(run(integrator("generalized alpha", 0.1, 1.0), problem, 0, 20,
                [&](const auto &)
                {
                  largest = std::max(
                      largest, std::abs(problem.mechanical_energy() - initial));
                }),
            200u);
  EXPECT_LT(largest, 1e-12 * initial);
  // The motion is not trivial: the first DoF has moved.
  EXPECT_GT(std::abs(problem.x()[0] - 1), 1e-2);
}

// Backward Euler on x'' + omega^2 x = 0: in (omega x, v) one step is the
// inverse of I + omega h J (J a quarter turn), whose singular values are
// both sqrt(1 + omega^2 h^2), so the energy falls by exactly that squared
// each step: first-order and dissipative.
TEST(TimeIntegration, ImplicitEulerDividesTheEnergyByOnePlusOmegaHSquared)
{
  const double omega = 3, h = 0.05;
  MassSpring   problem = oscillator(omega);
  problem.x()[0]       = 1;
  problem.save();
  double       previous = problem.mechanical_energy();
  const double ratio    = 1 / (1 + omega * omega * h * h);
  run(integrator("implicit euler", h), problem, 0, 1,
      [&](const auto &)
      {
        EXPECT_NEAR(problem.mechanical_energy() / previous, ratio, 1e-13);
        previous = problem.mechanical_energy();
      });
  EXPECT_NEAR(problem.mechanical_energy(),
              0.5 * omega * omega * std::pow(ratio, 20), 1e-12);
}

// The error at t = 1 of the oscillator x = cos(2 pi t) over one period:
// halving the step quarters it with generalized alpha (second order, with
// and without numerical damping) and halves it with backward Euler.
TEST(TimeIntegration, GeneralizedAlphaIsSecondOrderAndImplicitEulerFirst)
{
  for (const double rho_inf : {1.0, 0.8, 0.0})
  {
    SCOPED_TRACE("rho_inf = " + std::to_string(rho_inf));
    const double coarse = error_at_one("generalized alpha", 200, rho_inf),
                 fine   = error_at_one("generalized alpha", 400, rho_inf);
    EXPECT_NEAR(coarse / fine, 4, 0.1);
    EXPECT_LT(fine, 1e-2);
  }
  const double coarse = error_at_one("implicit euler", 800, 0.9),
               fine   = error_at_one("implicit euler", 1600, 0.9);
  EXPECT_NEAR(coarse / fine, 2, 0.05);
}

// Generalized alpha's amplification matrix on x'' + omega^2 x = 0, found
// by running single steps: its spectral radius tends to rho_inf as
// omega h grows (the damping of unresolved frequencies that rho_inf sets,
// Chung & Hulbert 1993), stays at 1 for resolved ones, and is 1 at every
// omega h when rho_inf = 1 (no numerical damping).
TEST(TimeIntegration, SpectralRadiusTendsToRhoInfinity)
{
  for (const double rho_inf : {0.0, 0.5, 0.9})
  {
    SCOPED_TRACE("rho_inf = " + std::to_string(rho_inf));
    EXPECT_NEAR(spectral_radius(1e5, rho_inf), rho_inf, 1e-3);
    EXPECT_NEAR(spectral_radius(1e-2, rho_inf), 1, 1e-5);
    // In between it lies between the two.
    const double middle = spectral_radius(3, rho_inf);
    EXPECT_LT(middle, 1);
    EXPECT_GT(middle, rho_inf);
  }
  for (const double omega_h : {1e-2, 1.0, 10.0, 1e5})
    EXPECT_NEAR(spectral_radius(omega_h, 1.0), 1, 1e-8) << omega_h;
}

// A soft mode (omega h = 0.01) and a stiff one (omega h = 1000), not
// coupled: with rho_inf = 0.5, 60 steps leave the soft mode's energy
// nearly whole and damp the stiff one by about 0.5^120 in energy (times a
// polynomial in the step count: the eigenvalue is nearly triple).
TEST(TimeIntegration, NumericalDampingRemovesTheStiffModeOnly)
{
  const double h = 0.01, soft = 1, stiff = 1e5;
  MassSpring   problem(matrix(2, {1.0, 0.0, 0.0, 1.0}),
                       matrix(2, {soft * soft, 0.0, 0.0, stiff * stiff}));
  problem.x()[0] = 1;
  problem.x()[1] = 1e-5; // the same energy in both modes
  problem.save();
  run(integrator("generalized alpha", h, 0.5), problem, 0, 60 * h);
  const double soft_energy  = 0.5 * (std::pow(problem.velocity()[0], 2) +
                                    std::pow(soft * problem.x()[0], 2));
  const double stiff_energy = 0.5 * (std::pow(problem.velocity()[1], 2) +
                                     std::pow(stiff * problem.x()[1], 2));
  EXPECT_NEAR(soft_energy, 0.5, 1e-6);
  EXPECT_LT(stiff_energy, 0.5 * 1e-20);
}

// On a linear problem the linearized implicit Euler (one correction from
// the start of the step) is the converged backward-Euler step: the same
// trajectory, here of a damped, loaded pair of masses.
TEST(TimeIntegration, LinearizedImplicitEulerIsTheConvergedStepOnALinearProblem)
{
  const auto make = []
  {
    MassSpring problem(matrix(2, {2.0, 0.0, 0.0, 1.0}),
                       matrix(2, {50.0, -20.0, -20.0, 40.0}),
                       matrix(2, {0.3, -0.1, -0.1, 0.2}));
    problem.load = [](double t, Vector<double> &f)
    {
      f[0] = std::sin(4 * t);
      f[1] = 1;
    };
    problem.velocity()[0] = 1;
    problem.save();
    return problem;
  };
  MassSpring          newton = make(), linearized = make();
  std::vector<double> trajectory;
  run(integrator("implicit euler", 0.02), newton, 0, 1,
      [&](const auto &) {
        trajectory.insert(trajectory.end(), {newton.x()[0], newton.x()[1]});
      });
  unsigned int step = 0;
  run(integrator("linearized implicit euler", 0.02), linearized, 0, 1,
      [&](const TimeIntegration::StepRecord &record)
      {
        EXPECT_EQ(record.iterations, 1u);
        EXPECT_NEAR(linearized.x()[0], trajectory[2 * step], 1e-12);
        EXPECT_NEAR(linearized.x()[1], trajectory[2 * step + 1], 1e-12);
        ++step;
      });
  EXPECT_EQ(step, 50u);
  EXPECT_NEAR(linearized.velocity()[0], newton.velocity()[0], 1e-11);
}

// A run continued from the Carry (generalized alpha's pseudo-acceleration
// and the step size) is the run that was not interrupted, to the bit; a
// fresh start at the same state (consistent acceleration) is not.
TEST(TimeIntegration, ARunContinuedFromItsCarryIsTheUninterruptedRun)
{
  const auto make = []
  {
    MassSpring problem(matrix(2, {1.0, 0.0, 0.0, 1.0}),
                       matrix(2, {40.0, -15.0, -15.0, 25.0}));
    problem.x()[0] = 1;
    problem.save();
    return problem;
  };
  // A step of 1/16 s: the times are exact, so both runs take the same steps.
  const TimeIntegration scheme = integrator("generalized alpha", 0.0625, 0.7);
  MassSpring            whole = make(), halves = make(), restarted = make();
  run(scheme, whole, 0, 2);
  TimeIntegration::Carry carry;
  run(scheme, halves, 0, 1, {}, &carry);
  ASSERT_TRUE(carry.filled());
  restarted.x()            = halves.x();
  restarted.velocity()     = halves.velocity();
  restarted.acceleration() = halves.acceleration();
  restarted.save();
  run(scheme, halves, 1, 2, {}, &carry);
  run(scheme, restarted, 1, 2); // no carry: starts afresh
  for (unsigned int i = 0; i < 2; ++i)
  {
    EXPECT_EQ(halves.x()[i], whole.x()[i]);
    EXPECT_EQ(halves.velocity()[i], whole.velocity()[i]);
  }
  EXPECT_GT(std::abs(restarted.x()[0] - whole.x()[0]), 1e-8);
}

// A step that fails (a non-finite residual for steps over 0.03 s) is
// undone and cut: the run reaches its end with every accepted step under
// the limit, and at rho_inf = 1 the energy is still conserved to
// round-off, which it would not be if a failed attempt left its rates
// behind.
TEST(TimeIntegration, CutsAFailedStepAndUndoesIt)
{
  MassSpring problem = oscillator(5);
  problem.x()[0]     = 1;
  problem.save();
  problem.longest_step = 0.03;
  const double initial = problem.mechanical_energy();
  double       reached = 0, largest = 0;
  run(integrator("generalized alpha", 0.05, 1.0, 1e-6), problem, 0, 1,
      [&](const TimeIntegration::StepRecord &record)
      {
        EXPECT_LE(record.dt, 0.03);
        reached = record.time;
        largest = std::max(largest, record.dt);
      });
  EXPECT_DOUBLE_EQ(reached, 1);
  EXPECT_GT(largest, 0.02); // it grew back after the cut
  EXPECT_NEAR(problem.mechanical_energy(), initial, 1e-12 * initial);
  // Out of cuts: the run stops with a NewtonFailure naming the step.
  problem.longest_step = 1e-3;
  EXPECT_THROW(
      run(integrator("generalized alpha", 0.05, 1.0, 1e-2), problem, 1, 2),
      NewtonFailure);
}
