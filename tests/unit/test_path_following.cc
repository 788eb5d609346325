// Static path following (solvers::PathFollowing) on two springs written
// here, whose equilibrium paths are known in closed form:
// - a hardening spring, x + c x^3 = s P: load control stops on the path at
//   every requested parameter, and recovers from forced failures by
//   cutting steps;
// - a snap-through spring, f(w) = w - 1.5 w^2 + 0.6 w^3 = s P, whose path
//   rises to a limit point (f' = 0 at w = 0.461), falls to a second one
//   (w = 1.206) and rises again, beside a linear spring k y = s Q that
//   makes the arc-length constraint couple two unknowns: the arc-length
//   method follows it through both limit points.

#include <coshell/solvers/path_following.h>

#include "solver_test_utilities.h"

#include <deal.II/lac/dynamic_sparsity_pattern.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace
{
  using coshell::solvers::testing::hardening_root;
  using coshell::solvers::testing::umfpack;
  using namespace dealii;
  using coshell::base::EvolutionProblem;
  using coshell::base::TangentMatrix;
  using coshell::solvers::LinearSolver;
  using coshell::solvers::NewtonFailure;
  using coshell::solvers::PathFollowing;

  /// r_i = s P_i - f_i(x_i), uncoupled, with f_i and f_i' given. The force
  /// scale has a floor: near s = 0 both forces vanish, and |r| must still
  /// be judged against something.
  class Springs : public EvolutionProblem
  {
  public:
    using Law = std::function<double(double)>;
    Springs(std::vector<double> load,
            std::vector<Law>    force,
            std::vector<Law>    stiffness)
        : load_(std::move(load)), force_(std::move(force)),
          stiffness_(std::move(stiffness)), x_(load_.size()), saved_(x_)
    {
      DynamicSparsityPattern dsp(x_.size(), x_.size());
      for (unsigned int i = 0; i < x_.size(); ++i)
        dsp.add(i, i);
      pattern_.copy_from(dsp);
    }

    /// An evaluation more than this past the saved path parameter gives a
    /// non-finite residual: a forced Newton failure.
    double longest_step = 1e300;

    const SparsityPattern &sparsity() const override
    {
      return pattern_;
    }
    void evaluate(Vector<double> &r, TangentMatrix *tangent) override
    {
      scale_ = 1e-3;
      for (unsigned int i = 0; i < x_.size(); ++i)
      {
        const double internal = force_[i](x_[i]), external = s_ * load_[i];
        r[i]   = external - internal;
        scale_ = std::max({scale_, std::abs(internal), std::abs(external)});
        if (tangent)
          tangent->serial().set(i, i, stiffness_[i](x_[i]));
      }
      if (s_ - saved_s_ > longest_step)
        r[0] = std::numeric_limits<double>::quiet_NaN();
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
      saved_   = x_;
      saved_s_ = s_;
    }
    void restore() override
    {
      x_ = saved_;
    }
    bool symmetric_tangent() const override
    {
      return true;
    }

    void set_path_parameter(double s) override
    {
      s_ = s;
    }
    void path_direction(Vector<double> &direction) override
    {
      direction.reinit(x_.size());
      for (unsigned int i = 0; i < x_.size(); ++i)
        direction[i] = load_[i];
    }
    // Statics only: the rates are never asked for.
    void            set_time(double) override {}
    void            step_increment(Vector<double> &) const override {}
    void            set_step_increment(const Vector<double> &) override {}
    Vector<double> &velocity() override
    {
      return unused_;
    }
    Vector<double> &acceleration() override
    {
      return unused_;
    }
    void set_rate_coefficients(double, double) override {}
    void mass_matrix(TangentMatrix &) override {}

    const Vector<double> &x() const
    {
      return x_;
    }
    double parameter() const
    {
      return s_;
    }

  private:
    std::vector<double> load_;
    std::vector<Law>    force_, stiffness_;
    Vector<double>      x_, saved_, unused_;
    SparsityPattern     pattern_;
    double              s_ = 0, saved_s_ = 0, scale_ = 1e-3;
  };

  /// x + c x^3 = s P.
  Springs hardening(double c, double P)
  {
    return Springs({P}, {[c](double x) { return x + c * x * x * x; }},
                   {[c](double x) { return 1 + 3 * c * x * x; }});
  }

  double snap_force(double w)
  {
    return w - 1.5 * w * w + 0.6 * w * w * w;
  }
  double snap_stiffness(double w)
  {
    return 1 - 3 * w + 1.8 * w * w;
  }

  /// f(w) = s P for the snap-through spring, P = 1, and k y = s Q,
  /// k = 4, Q = 1.
  Springs snap_through()
  {
    return Springs({1.0, 1.0}, {snap_force, [](double y) { return 4 * y; }},
                   {snap_stiffness, [](double) { return 4.0; }});
  }

  PathFollowing path_following(const std::string &method,
                               unsigned int       load_steps,
                               unsigned int       max_cuts = 12)
  {
    ParameterHandler prm;
    PathFollowing::declare_parameters(prm);
    prm.enter_subsection("Nonlinear solver");
    prm.set("Method", method);
    prm.set("Load steps", std::to_string(load_steps));
    prm.set("Maximum step cuts", std::to_string(max_cuts));
    prm.set("Residual tolerance", "1e-11");
    prm.leave_subsection();
    PathFollowing path;
    path.parse_parameters(prm);
    return path;
  }

  /// One converged step as the observer saw it.
  struct PathPoint
  {
    double       parameter;
    unsigned int iterations;
    double       x0, x1;
  };

  std::vector<PathPoint> follow(const PathFollowing       &path,
                                Springs                   &problem,
                                const std::vector<double> &stops,
                                std::string               *log_text = nullptr)
  {
    std::vector<PathPoint> points;
    std::ostringstream     log;
    path.run(
        problem, umfpack(), stops,
        [&](unsigned int, double parameter, unsigned int iterations)
        {
          points.push_back({parameter, iterations, problem.x()[0],
                            problem.x().size() > 1 ? problem.x()[1] : 0});
        },
        {}, log);
    if (log_text)
      *log_text = log.str();
    return points;
  }
} // namespace

// Load control in steps of 1/4 that never step over a stop: it converges
// exactly at 0.1, 0.3 and 0.62 and at the quarter steps between, each on
// the analytic path (the bisection root of x + c x^3 = s P).
TEST(PathFollowing, LoadControlStopsOnTheAnalyticPath)
{
  const double              c = 2, P = 3;
  Springs                   problem = hardening(c, P);
  const std::vector<double> stops   = {0.1, 0.3, 0.62};
  const auto points = follow(path_following("load control", 4), problem, stops);
  const std::vector<double> expected = {0.1, 0.3, 0.55, 0.62, 0.87, 1.0};
  ASSERT_EQ(points.size(), expected.size());
  for (unsigned int k = 0; k < points.size(); ++k)
  {
    EXPECT_NEAR(points[k].parameter, expected[k], 1e-14);
    EXPECT_NEAR(points[k].x0, hardening_root(points[k].parameter * P, c),
                1e-10);
  }
  for (const double stop : stops) // exactly, not to round-off
    EXPECT_NE(std::find_if(points.begin(), points.end(),
                           [stop](const PathPoint &p)
                           { return p.parameter == stop; }),
              points.end())
        << stop;
}

// Steps longer than 0.15 in the path parameter fail (non-finite residual):
// starting from steps of 1/2, load control cuts until a step converges,
// grows again after easy ones, and reaches s = 1 on the path with every
// accepted step under the limit. With one cut allowed it gives up with a
// message that names the step and the cause.
TEST(PathFollowing, StepCuttingRecoversFromForcedFailures)
{
  const double c = 0.5, P = 4;
  Springs      problem = hardening(c, P);
  problem.longest_step = 0.15;
  std::string log;
  const auto  points =
      follow(path_following("load control", 2), problem, {}, &log);
  ASSERT_FALSE(points.empty());
  double previous = 0;
  for (const PathPoint &point : points)
  {
    EXPECT_LE(point.parameter - previous, 0.15 + 1e-12);
    EXPECT_NEAR(point.x0, hardening_root(point.parameter * P, c), 1e-10);
    previous = point.parameter;
  }
  EXPECT_DOUBLE_EQ(points.back().parameter, 1);
  EXPECT_NE(log.find("cutting the increment"), std::string::npos) << log;

  Springs again      = hardening(c, P);
  again.longest_step = 0.15;
  try
  {
    follow(path_following("load control", 2, 1), again, {});
    FAIL() << "two cuts were needed, one allowed";
  }
  catch (const NewtonFailure &failure)
  {
    const std::string message = failure.what();
    EXPECT_NE(message.find("load step from load factor 0 to 0.25 failed "
                           "after 1 step cuts"),
              std::string::npos)
        << message;
    EXPECT_NE(message.find("diverged"), std::string::npos) << message;
  }
}

// Crisfield's arc length on the snap-through spring: every converged point
// lies on the analytic path (f(w) = s, 4 y = s), w grows throughout, and
// the load factor rises while w is below the first limit point
// (w = 0.461, load f = 0.201), falls between it and the second (w = 1.206,
// load 0.077) and rises again after it, past 1: the path that load control
// can only jump across.
TEST(PathFollowing, ArcLengthFollowsTheSnapThroughPastBothLimitPoints)
{
  Springs    problem = snap_through();
  const auto points  = follow(path_following("arc length", 20), problem, {});
  // The limit points, from f' = 1 - 3 w + 1.8 w^2 = 0.
  const double w_max = (3 - std::sqrt(1.8)) / 3.6,
               w_min = (3 + std::sqrt(1.8)) / 3.6;
  std::array<unsigned int, 3> on_branch{}; // points before, between, after
  unsigned int                unloading = 0;
  PathPoint                   previous{0, 0, 0, 0};
  for (unsigned int k = 0; k < points.size(); ++k)
  {
    const PathPoint &p = points[k];
    SCOPED_TRACE("step " + std::to_string(k + 1) + ": w = " +
                 std::to_string(p.x0) + ", s = " + std::to_string(p.parameter));
    EXPECT_NEAR(snap_force(p.x0), p.parameter, 1e-9);
    EXPECT_NEAR(4 * p.x1, p.parameter, 1e-9);
    EXPECT_GT(p.x0, previous.x0);
    ++on_branch[p.x0 < w_max ? 0 : p.x0 < w_min ? 1 : 2];
    // Where f' has one sign between two points, the load follows it.
    if (previous.x0 > w_max && p.x0 < w_min)
    {
      EXPECT_LT(p.parameter, previous.parameter);
      ++unloading;
    }
    if (p.x0 < w_max || previous.x0 > w_min)
    {
      EXPECT_GT(p.parameter, previous.parameter);
    }
    // Below the second limit point no load exceeds the first limit load.
    if (p.x0 < w_min)
    {
      EXPECT_LE(p.parameter, snap_force(w_max) + 1e-12);
    }
    previous = p;
  }
  EXPECT_GE(on_branch[0], 1u);
  EXPECT_GE(on_branch[1], 2u);
  EXPECT_GE(on_branch[2], 1u);
  EXPECT_GE(unloading, 1u);
  // It ends at Maximum load factor = 1 or just past it, on the far branch.
  ASSERT_FALSE(points.empty());
  EXPECT_GE(points.back().parameter, 1 - 1e-12);
  EXPECT_GT(points.back().x0, w_min);
}
