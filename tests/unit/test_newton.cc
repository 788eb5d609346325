// The physics-free Newton solver and step controller on small algebraic
// problems with known solutions; the line searches (the energy slope and
// Armijo's on the potential) and the tolerances on the correction.

#include <coshell/solvers/newton.h>

#include "solver_test_utilities.h"

#include <deal.II/lac/dynamic_sparsity_pattern.h>

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace
{
  using coshell::solvers::testing::hardening_root;
  using coshell::solvers::testing::umfpack;
  using namespace dealii;
  using coshell::base::NonlinearProblem;
  using coshell::base::TangentMatrix;
  using coshell::solvers::LinearSolver;
  using coshell::solvers::Newton;
  using coshell::solvers::NewtonFailure;
  using coshell::solvers::NewtonIteration;
  using coshell::solvers::NewtonParameters;
  using coshell::solvers::StepController;

  /// r_i(x) = load_i - (k x_i + c x_i^3) - coupling (x_i - x_j), i != j;
  /// unknown 'fixed' (if any) is prescribed to 'prescribed_value' through
  /// the pending-increment mechanism.
  class CubicSprings : public coshell::base::NonlinearProblem
  {
  public:
    CubicSprings(std::vector<double> load,
                 double              c,
                 int                 fixed            = -1,
                 double              prescribed_value = 0)
        : load_(std::move(load)), c_(c), fixed_(fixed),
          prescribed_(prescribed_value), x_(load_.size()), saved_(x_)
    {
      DynamicSparsityPattern dsp(x_.size(), x_.size());
      for (unsigned int i = 0; i < x_.size(); ++i)
        for (unsigned int j = 0; j < x_.size(); ++j)
          dsp.add(i, j);
      pattern_.copy_from(dsp);
    }

    const SparsityPattern &sparsity() const override
    {
      return pattern_;
    }

    void evaluate(Vector<double>               &r,
                  coshell::base::TangentMatrix *tangent) override
    {
      SparseMatrix<double> *K = tangent ? &tangent->serial() : nullptr;
      scale_                  = 0;
      for (unsigned int i = 0; i < x_.size(); ++i)
      {
        const double internal = x_[i] + c_ * std::pow(x_[i], 3) +
                                coupling * (x_.size() * x_[i] - sum());
        r[i]   = load_[i] - internal;
        scale_ = std::max({scale_, std::abs(internal), std::abs(load_[i])});
        if (K)
          for (unsigned int j = 0; j < x_.size(); ++j)
            K->set(i, j,
                   (i == j ? spring_stiffness(x_[i]) + coupling : 0) -
                       (i == j ? 0 : coupling));
      }
      if (fixed_ >= 0)
      {
        // Constrained row: identity, residual = remaining increment.
        r[fixed_] = 0;
        if (K)
          for (unsigned int j = 0; j < x_.size(); ++j)
            K->set(fixed_, j, fixed_ == int(j) ? 1 : 0);
      }
      ++evaluations;
      tangent_evaluations += K != nullptr;
    }

    double force_scale() const override
    {
      return scale_;
    }

    /// The potential whose negative gradient r is, when 'has_energy'.
    double energy() override
    {
      return has_energy ? potential() : NonlinearProblem::energy();
    }

    /// sum_i (x_i^2 / 2 + c x_i^4 / 4 - load_i x_i) + coupling / 2
    /// sum_{i<j} (x_i - x_j)^2.
    double potential() const
    {
      double value = 0;
      for (unsigned int i = 0; i < x_.size(); ++i)
      {
        value += 0.5 * x_[i] * x_[i] + 0.25 * c_ * std::pow(x_[i], 4) -
                 load_[i] * x_[i];
        for (unsigned int j = i + 1; j < x_.size(); ++j)
          value += 0.5 * coupling * (x_[i] - x_[j]) * (x_[i] - x_[j]);
      }
      return value;
    }

    bool prescribed_increment_pending() const override
    {
      return fixed_ >= 0 && std::abs(x_[fixed_] - prescribed_) > 1e-14;
    }

    void distribute(Vector<double> &dx) const override
    {
      if (fixed_ >= 0)
        dx[fixed_] = prescribed_ - x_[fixed_];
    }

    void apply_increment(const Vector<double> &dx) override
    {
      x_ += dx;
    }

    void save() override
    {
      saved_ = x_;
    }

    void restore() override
    {
      x_ = saved_;
    }

    bool symmetric_tangent() const override
    {
      return true;
    }

    bool use_convex_tangent() override
    {
      if (!offers_convex_tangent || convex_)
        return false;
      convex_ = true;
      ++switches;
      return true;
    }

    const Vector<double> &x() const
    {
      return x_;
    }

    bool         has_energy          = false;
    double       coupling            = 0;
    unsigned int evaluations         = 0;
    unsigned int tangent_evaluations = 0;
    /// The convex tangent floors the spring stiffness at 1 (a modified
    /// Newton whose corrections always descend).
    bool         offers_convex_tangent = false;
    unsigned int switches              = 0;

  private:
    double spring_stiffness(double x) const
    {
      const double exact = 1 + 3 * c_ * x * x;
      return convex_ ? std::max(exact, 1.0) : exact;
    }

    double sum() const
    {
      double s = 0;
      for (const double xi : x_)
        s += xi;
      return s; // n x_i - sum_j x_j: springs between every pair
    }

    std::vector<double> load_;
    double              c_;
    int                 fixed_;
    double              prescribed_;
    Vector<double>      x_, saved_;
    SparsityPattern     pattern_;
    double              scale_  = 0;
    bool                convex_ = false;
  };

} // namespace

TEST(Newton, SolvesUncoupledCubicsToTheBisectionRoot)
{
  CubicSprings           problem({2.0, -5.0}, 0.5);
  const NewtonParameters parameters;
  Newton                 newton(parameters, umfpack());
  std::vector<double>    residuals;
  const unsigned int     iterations =
      newton.solve(problem, [&](const NewtonIteration &record)
                   { residuals.push_back(record.relative_residual); });
  EXPECT_NEAR(problem.x()[0], hardening_root(2.0, 0.5), 1e-9);
  EXPECT_NEAR(problem.x()[1], hardening_root(-5.0, 0.5), 1e-9);
  EXPECT_LE(iterations, 8u);
  // Quadratic convergence: r_{k+1} <= C r_k^2 in the last steps.
  ASSERT_GE(residuals.size(), 3u);
  const std::size_t n = residuals.size();
  const double order  = std::log(residuals[n - 1]) / std::log(residuals[n - 2]);
  EXPECT_GT(order, 1.8);
}

TEST(Newton, AssemblesNoTangentForTheEvaluationThatEndsTheSolve)
{
  // Quadratic convergence lets Newton predict that the last evaluation
  // ends the solve: each of its corrections needed one tangent, the last
  // evaluation none, and the root is the same.
  CubicSprings       problem({2.0, -5.0}, 0.5);
  Newton             newton(NewtonParameters(), umfpack());
  const unsigned int iterations = newton.solve(problem);
  EXPECT_EQ(problem.tangent_evaluations, iterations);
  EXPECT_GT(problem.evaluations, problem.tangent_evaluations);
  EXPECT_NEAR(problem.x()[0], hardening_root(2.0, 0.5), 1e-9);
  EXPECT_NEAR(problem.x()[1], hardening_root(-5.0, 0.5), 1e-9);
}

TEST(Newton, ConvergesWhenTheExternalLoadIsZero)
{
  // Displacement-driven: no load, unknown 0 prescribed to 1.5, unknown 1
  // coupled to it. The force scale is the internal force, so the first
  // iteration is not counted as diverged.
  CubicSprings problem({0.0, 0.0}, 0.2, 0, 1.5);
  problem.coupling = 3;
  NewtonParameters parameters;
  parameters.residual_tolerance = 1e-12;
  Newton             newton(parameters, umfpack());
  const unsigned int iterations = newton.solve(problem);
  EXPECT_NEAR(problem.x()[0], 1.5, 1e-14);
  // Row 1: -(x1 + c x1^3 + 3 (x1 - x0)) = 0.
  const double x1 = problem.x()[1];
  EXPECT_NEAR(x1 + 0.2 * x1 * x1 * x1 + 3 * (x1 - 1.5), 0, 1e-8);
  EXPECT_GE(iterations, 2u);
}

TEST(Newton, DoesNotStopWhilePrescribedIncrementIsPending)
{
  // Zero residual everywhere at the start, but the prescribed unknown has
  // not moved yet: Newton must take at least one correction.
  CubicSprings problem({0.0}, 0.0, 0, 2.0);
  Newton       newton(NewtonParameters(), umfpack());
  EXPECT_GE(newton.solve(problem), 1u);
  EXPECT_NEAR(problem.x()[0], 2.0, 1e-14);
}

TEST(Newton, ReportsDivergenceAndIterationLimit)
{
  CubicSprings     problem({1e6}, 1.0);
  NewtonParameters parameters;
  parameters.max_iterations = 2;
  Newton newton(parameters, umfpack());
  EXPECT_THROW(newton.solve(problem), NewtonFailure);
}

TEST(Newton, SingleCorrectionIsOneLinearSolve)
{
  // On a linear problem one correction is exact.
  CubicSprings problem({3.0, -1.0}, 0.0);
  Newton       newton(NewtonParameters(), umfpack());
  newton.single_correction(problem);
  EXPECT_NEAR(problem.x()[0], 3.0, 1e-14);
  EXPECT_NEAR(problem.x()[1], -1.0, 1e-14);
}

TEST(Newton, LineSearchLeavesTheIterateUnchangedBetweenTrials)
{
  CubicSprings     problem({50.0}, 1.0);
  NewtonParameters parameters;
  parameters.line_search        = true;
  parameters.residual_tolerance = 1e-12;
  Newton newton(parameters, umfpack());
  newton.solve(problem);
  EXPECT_NEAR(problem.x()[0], hardening_root(50.0, 1.0), 1e-9);
}

TEST(Newton, LineSearchKeepsTheEvaluationOfAnAcceptedWholeStep)
{
  // Where every whole correction is accepted, the line search's trial is
  // the next iteration's evaluation: Newton with the line search evaluates
  // (with and without the tangent) exactly as often as without it, and
  // reaches the same iterate to the bit.
  CubicSprings       plain({0.5, -0.8}, 0.1), searched({0.5, -0.8}, 0.1);
  NewtonParameters   parameters;
  const unsigned int iterations = Newton(parameters, umfpack()).solve(plain);
  parameters.line_search        = true;
  EXPECT_EQ(Newton(parameters, umfpack()).solve(searched), iterations);
  EXPECT_EQ(searched.evaluations, plain.evaluations);
  EXPECT_EQ(searched.tangent_evaluations, plain.tangent_evaluations);
  EXPECT_EQ(searched.x()[0], plain.x()[0]);
  EXPECT_EQ(searched.x()[1], plain.x()[1]);
}

TEST(Newton, LineSearchEvaluatesEachScaleOnce)
{
  // A tangent 1 / 0.03 times too stiff: the slope drops by 3 % at the
  // whole correction, the secant asks for more than 1 and is clamped back
  // to 1, which was tried. One evaluation per scale: the solve's first
  // evaluation, one trial, the next iteration's (then the limit).
  class TooStiffTangent : public CubicSprings
  {
  public:
    TooStiffTangent() : CubicSprings({1.0}, 0.0) {}
    void evaluate(Vector<double>               &r,
                  coshell::base::TangentMatrix *tangent) override
    {
      CubicSprings::evaluate(r, tangent);
      if (tangent)
        tangent->serial() *= 1 / 0.03;
    }
  } problem;
  NewtonParameters parameters;
  parameters.line_search    = true;
  parameters.max_iterations = 1;
  EXPECT_THROW(Newton(parameters, umfpack()).solve(problem), NewtonFailure);
  EXPECT_EQ(problem.evaluations, 3u);
  EXPECT_NEAR(problem.x()[0], 0.03, 1e-15);
}

// Armijo's line search on the potential: from x = 0 the whole Newton
// correction of the stiffening spring overshoots (tangent 1, load 50), so
// the search halves it; every accepted iterate lowers the potential, and
// Newton ends at the root.
TEST(Newton, ArmijoLineSearchLowersTheEnergyAtEveryCorrection)
{
  CubicSprings problem({50.0, -20.0}, 1.0);
  problem.has_energy = true;
  problem.coupling   = 2;
  NewtonParameters parameters;
  parameters.line_search        = true;
  parameters.line_search_rule   = NewtonParameters::LineSearchRule::armijo;
  parameters.residual_tolerance = 1e-12;
  std::vector<double> energies{problem.potential()};
  Newton(parameters, umfpack())
      .solve(problem,
             [&](const NewtonIteration &record)
             {
               if (record.correction_norm > 0)
                 energies.push_back(problem.potential());
             });
  ASSERT_GE(energies.size(), 3u);
  for (unsigned int k = 1; k < energies.size(); ++k)
    EXPECT_LE(energies[k], energies[k - 1]) << "correction " << k;
  // The root of both rows: -(x_i + x_i^3 + 2 (x_i - x_j)) + load_i = 0.
  const double x0 = problem.x()[0], x1 = problem.x()[1];
  EXPECT_NEAR(50 - (x0 + std::pow(x0, 3) + 2 * (x0 - x1)), 0, 1e-9);
  EXPECT_NEAR(-20 - (x1 + std::pow(x1, 3) + 2 * (x1 - x0)), 0, 1e-9);
}

// Without an energy (energy() is NaN) the Armijo rule falls back to the
// energy-slope search: the same iterates to the bit.
TEST(Newton, ArmijoWithoutAnEnergyIsTheSlopeSearch)
{
  CubicSprings     slope({50.0}, 1.0), armijo({50.0}, 1.0);
  NewtonParameters parameters;
  parameters.line_search        = true;
  const unsigned int iterations = Newton(parameters, umfpack()).solve(slope);
  parameters.line_search_rule   = NewtonParameters::LineSearchRule::armijo;
  EXPECT_EQ(Newton(parameters, umfpack()).solve(armijo), iterations);
  EXPECT_EQ(armijo.x()[0], slope.x()[0]);
  EXPECT_EQ(armijo.evaluations, slope.evaluations);
}

// The velocity tolerance is a correction tolerance of tol * dt: a solve
// with 'Velocity tolerance' v and time step h takes the same corrections
// to the same iterate as one with 'Correction tolerance' v h, stops
// earlier than the residual test alone, and is not used in statics (no
// time step).
TEST(Newton, VelocityToleranceIsACorrectionToleranceTimesTheStep)
{
  const double     v = 0.2, h = 0.01;
  NewtonParameters parameters;
  parameters.residual_tolerance = 1e-14;
  CubicSprings       plain({2.0, -5.0}, 0.5);
  const unsigned int full = Newton(parameters, umfpack()).solve(plain);

  CubicSprings by_length({2.0, -5.0}, 0.5), by_velocity({2.0, -5.0}, 0.5),
      in_statics({2.0, -5.0}, 0.5);
  parameters.correction_tolerance = v * h;
  const unsigned int length_iterations =
      Newton(parameters, umfpack()).solve(by_length);
  parameters.correction_tolerance = 0;
  parameters.velocity_tolerance   = v;
  EXPECT_EQ(Newton(parameters, umfpack()).solve(by_velocity, {}, h),
            length_iterations);
  EXPECT_EQ(by_velocity.x()[0], by_length.x()[0]);
  EXPECT_LT(length_iterations, full);
  EXPECT_EQ(Newton(parameters, umfpack()).solve(in_statics), full);
}

TEST(Newton, FailureMessageNamesAnIndefiniteTangent)
{
  // A softening spring, f = x - x^3, carries at most 2 / sqrt(27) = 0.385:
  // under a load of 1 there is no equilibrium, and past x = 1 / sqrt(3)
  // the tangent 1 - 3 x^2 is negative, so Newton's corrections climb the
  // energy; the failure message says so.
  CubicSprings     problem({1.0}, -1.0);
  NewtonParameters parameters;
  parameters.line_search    = true;
  parameters.max_iterations = 12;
  Newton newton(parameters, umfpack());
  try
  {
    newton.solve(problem);
    FAIL() << "Newton converged where there is no equilibrium";
  }
  catch (const NewtonFailure &failure)
  {
    const std::string message = failure.what();
    EXPECT_NE(message.find("did not converge in 12 iterations"),
              std::string::npos)
        << message;
    EXPECT_NE(message.find("climbed the energy"), std::string::npos) << message;
  }
}

TEST(Newton, SwitchesToTheConvexTangentWhenACorrectionClimbs)
{
  // Softening spring x - x^3 under 0.2: a stable equilibrium near 0.20 and
  // an unstable one near 0.88 (tangent 1 - 3 x^2 < 0 past 1/sqrt(3)).
  // From x = 0.75 the exact tangent is negative, so Newton climbs to the
  // unstable one; offered a convex tangent, it switches once, at the
  // first climbing correction, and descends to the stable one.
  const double     unstable_limit = 1 / std::sqrt(3.0);
  NewtonParameters parameters;
  parameters.residual_tolerance = 1e-12;
  parameters.energy_tolerance   = 0; // the convex tangent converges linearly
  parameters.climbs_before_convex_tangent = 1;
  Newton newton(parameters, umfpack());
  for (const bool offered : {false, true})
  {
    SCOPED_TRACE(offered ? "convex tangent offered" : "exact tangent only");
    CubicSprings problem({0.2}, -1.0);
    problem.offers_convex_tangent = offered;
    Vector<double> start(1);
    start[0] = 0.75;
    problem.apply_increment(start);
    newton.solve(problem);
    const double x = problem.x()[0];
    EXPECT_NEAR(x - x * x * x, 0.2, 1e-10);
    EXPECT_EQ(problem.switches, offered ? 1u : 0u);
    if (offered)
      EXPECT_LT(x, unstable_limit);
    else
      EXPECT_GT(x, unstable_limit);
  }
}

TEST(StepController, CutsGrowsAndGivesUp)
{
  StepController control({0.25, 0.01, 0.25, 2, 6, 2, 0.5});
  EXPECT_DOUBLE_EQ(control.size(), 0.25);
  control.failure(0.25, "step", "no");
  EXPECT_DOUBLE_EQ(control.size(), 0.125);
  control.success(3);
  EXPECT_DOUBLE_EQ(control.size(), 0.25); // grown, capped at the maximum
  control.failure(0.25, "step", "no");
  control.success(10); // hard step: no growth
  EXPECT_DOUBLE_EQ(control.size(), 0.125);
  control.failure(0.125, "step", "no");
  control.failure(0.0625, "step", "no");
  try
  {
    control.failure(0.03125, "step from 0 to 1", "cause");
    FAIL() << "a third consecutive cut must throw";
  }
  catch (const NewtonFailure &failure)
  {
    EXPECT_EQ(std::string(failure.what()),
              "step from 0 to 1 failed after 2 step cuts: cause");
  }
}

TEST(StepController, StopsBelowTheMinimumStep)
{
  StepController control({0.1, 0.04, 0.1, 10, 6, 2, 0.5});
  control.failure(0.1, "step", "cause");
  EXPECT_THROW(control.failure(0.05, "step", "cause"), NewtonFailure);
}
