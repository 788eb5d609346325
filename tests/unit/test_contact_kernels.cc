// Contact kernels: distances and their derivatives, the barrier and
// penalty potentials, the positive semi-definite projection and additive
// CCD, each against finite differences or closed forms.

#include <coshell/contact/barrier.h>
#include <coshell/contact/ccd.h>
#include <coshell/contact/distances.h>

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <utility>
#include <vector>

namespace
{
  using namespace coshell::contact;
  using dealii::Point;
  using dealii::Tensor;

  using DistanceFunction = std::function<SquaredDistance(const Point<3> &,
                                                         const Point<3> &,
                                                         const Point<3> &,
                                                         const Point<3> &,
                                                         bool)>;

  SquaredDistance
  at(const DistanceFunction &f, const Coordinates12 &x, bool derivatives)
  {
    const auto p = [&](unsigned int i)
    { return Point<3>(x[3 * i], x[3 * i + 1], x[3 * i + 2]); };
    return f(p(0), p(1), p(2), p(3), derivatives);
  }

  /// Central differences of the value and of the gradient, against the
  /// analytic gradient and Hessian; returns the feature at x.
  unsigned int check_derivatives(const DistanceFunction &f,
                                 const Coordinates12    &x)
  {
    const SquaredDistance exact = at(f, x, true);
    const double          h     = 1e-6;
    double                scale = 0;
    for (unsigned int i = 0; i < 12; ++i)
      scale = std::max(scale, std::abs(exact.gradient[i]));
    for (unsigned int i = 0; i < 12; ++i)
    {
      Coordinates12 plus = x, minus = x;
      plus[i] += h;
      minus[i] -= h;
      const auto fp = at(f, plus, true), fm = at(f, minus, true);
      EXPECT_NEAR((fp.value - fm.value) / (2 * h), exact.gradient[i],
                  1e-6 * scale)
          << "gradient entry " << i;
      for (unsigned int j = 0; j < 12; ++j)
        EXPECT_NEAR((fp.gradient[j] - fm.gradient[j]) / (2 * h),
                    exact.hessian[i][j], 2e-5 * std::max(1.0, scale))
            << "Hessian entry " << i << ", " << j;
    }
    return exact.feature;
  }

  // Triangle a = (0,0,0), b = (1,0,0), c = (0,1,0) and a point above
  // each of its seven regions.
  Coordinates12 point_over(double px, double py, double pz)
  {
    return {px, py, pz, 0, 0, 0, 1.0, 0.1, 0.05, 0.1, 1.0, -0.05};
  }
} // namespace

TEST(ContactDistances, PointTriangleDerivativesInEveryRegion)
{
  const DistanceFunction f = point_triangle_distance;
  EXPECT_EQ(check_derivatives(f, point_over(-0.3, -0.2, 0.4)), 0u);
  EXPECT_EQ(check_derivatives(f, point_over(1.5, -0.1, 0.3)), 1u);
  EXPECT_EQ(check_derivatives(f, point_over(-0.2, 1.6, -0.3)), 2u);
  EXPECT_EQ(check_derivatives(f, point_over(0.5, -0.4, 0.2)), 3u);
  EXPECT_EQ(check_derivatives(f, point_over(-0.4, 0.5, 0.2)), 4u);
  EXPECT_EQ(check_derivatives(f, point_over(0.8, 0.8, 0.3)), 5u);
  EXPECT_EQ(check_derivatives(f, point_over(0.25, 0.3, 0.35)), 6u);
}

TEST(ContactDistances, PointTriangleValuesAgainstClosedForms)
{
  const Point<3> a(0, 0, 0), b(2, 0, 0), c(0, 2, 0);
  // Above the face: the height; beyond an edge: to the edge; a vertex.
  EXPECT_NEAR(
      point_triangle_distance(Point<3>(0.5, 0.5, 0.7), a, b, c, false).value,
      0.49, 1e-14);
  EXPECT_NEAR(point_triangle_distance(Point<3>(1, -1, 1), a, b, c, false).value,
              2.0, 1e-14);
  EXPECT_NEAR(point_triangle_distance(Point<3>(3, -1, 0), a, b, c, false).value,
              2.0, 1e-14);
  // Beyond the hypotenuse: distance to the line x + y = 2.
  EXPECT_NEAR(point_triangle_distance(Point<3>(2, 2, 0), a, b, c, false).value,
              2.0, 1e-14);
}

TEST(ContactDistances, SegmentSegmentDerivativesInteriorAndClamped)
{
  const DistanceFunction f = segment_segment_distance;
  // Crossing skew segments: both parameters interior.
  check_derivatives(f, {0, 0, 0, 1, 0.1, 0, 0.4, -0.5, 0.3, 0.6, 0.7, 0.35});
  // The second segment beyond the end of the first: s clamped to 1.
  check_derivatives(f, {0, 0, 0, 1, 0, 0, 1.5, -0.5, 0.3, 1.6, 0.7, 0.2});
  // Both clamped: end to end.
  check_derivatives(f, {0, 0, 0, 1, 0, 0, 1.5, 0.2, 0.3, 2.5, 0.9, 0.2});
  const auto d = segment_segment_distance(Point<3>(0, 0, 0), Point<3>(1, 0, 0),
                                          Point<3>(0.5, -1, 0.3),
                                          Point<3>(0.5, 1, 0.3), false);
  EXPECT_NEAR(d.value, 0.09, 1e-14);
  EXPECT_NEAR(d.parameters[0], 0.5, 1e-14);
  EXPECT_NEAR(d.parameters[1], 0.5, 1e-14);
}

// The slope of a driven obstacle's force (the interactive protocol) takes
// the obstacle's couplings from the shell's block of the pair's Hessian.
// That holds because a distance depends on differences of positions only:
// moving all four points by one vector changes nothing, so the gradient's
// four parts sum to zero and the Hessian annihilates such a move, in every
// region of the point-triangle distance and for segments.
TEST(ContactDistances, DerivativesAreInvariantUnderTranslation)
{
  const std::vector<std::pair<DistanceFunction, Coordinates12>> cases = {
      {point_triangle_distance, point_over(-0.3, -0.2, 0.4)},
      {point_triangle_distance, point_over(0.5, -0.4, 0.2)},
      {point_triangle_distance, point_over(0.8, 0.8, 0.3)},
      {point_triangle_distance, point_over(0.25, 0.3, 0.35)},
      {segment_segment_distance,
       {0, 0, 0, 1, 0.1, 0, 0.4, -0.5, 0.3, 0.6, 0.7, 0.35}},
      {segment_segment_distance,
       {0, 0, 0, 1, 0, 0, 1.5, -0.5, 0.3, 1.6, 0.7, 0.2}}};
  const Tensor<1, 3> move({0.3, -0.7, 0.5});
  for (const auto &[f, x] : cases)
  {
    const SquaredDistance d = at(f, x, true);
    for (unsigned int c = 0; c < 3; ++c)
    {
      double sum = 0;
      for (unsigned int k = 0; k < 4; ++k)
        sum += d.gradient[3 * k + c];
      EXPECT_NEAR(sum, 0, 1e-14);
    }
    for (unsigned int i = 0; i < 12; ++i)
    {
      double moved = 0;
      for (unsigned int j = 0; j < 12; ++j)
        moved += d.hessian[i][j] * move[j % 3];
      EXPECT_NEAR(moved, 0, 1e-13) << "Hessian row " << i;
    }
  }
}

TEST(ContactPotentials, BarrierDerivativesAndSupport)
{
  const double g_hat = 0.2, h = 1e-7;
  for (const double g : {0.01, 0.05, 0.1, 0.19})
  {
    const auto b = log_barrier(g, g_hat), bp = log_barrier(g + h, g_hat),
               bm = log_barrier(g - h, g_hat);
    EXPECT_NEAR((bp.value - bm.value) / (2 * h), b.first,
                1e-6 * std::abs(b.first) + 1e-12);
    EXPECT_NEAR((bp.first - bm.first) / (2 * h), b.second,
                1e-5 * b.second + 1e-9);
    EXPECT_GT(b.value, 0);
    EXPECT_LT(b.first, 0); // repulsive
  }
  // C2 at the activation distance, zero beyond, infinite at contact.
  const auto edge = log_barrier(g_hat * (1 - 1e-9), g_hat);
  EXPECT_NEAR(edge.value, 0, 1e-12);
  EXPECT_NEAR(edge.first, 0, 1e-9);
  EXPECT_NEAR(edge.second, 0, 1e-7);
  EXPECT_EQ(log_barrier(0.3, g_hat).value, 0);
  EXPECT_TRUE(std::isinf(log_barrier(0, g_hat).value));
}

TEST(ContactPotentials, PenaltyIsC2AndQuadraticBeyondTheSmoothing)
{
  const double eps = 0.01, h = 1e-7;
  for (const double g : {0.005, -0.004, -0.02, -0.5})
  {
    const auto p = smoothed_penalty(g, eps), pp = smoothed_penalty(g + h, eps),
               pm = smoothed_penalty(g - h, eps);
    EXPECT_NEAR((pp.value - pm.value) / (2 * h), p.first, 1e-6);
    EXPECT_NEAR((pp.first - pm.first) / (2 * h), p.second, 1e-5);
  }
  const auto below = smoothed_penalty(-eps * (1 - 1e-9), eps),
             above = smoothed_penalty(-eps * (1 + 1e-9), eps);
  EXPECT_NEAR(below.value, above.value, 1e-12);
  EXPECT_NEAR(below.first, above.first, 1e-9);
  EXPECT_NEAR(below.second, above.second, 1e-6);
  // Force = -(x - eps/2) for a penetration x beyond eps.
  EXPECT_NEAR(smoothed_penalty(-0.5, eps).first, -(0.5 - eps / 2), 1e-14);
}

TEST(ContactPotentials, ProjectionKeepsPositivePartOnly)
{
  // diag(3, -2) rotated by 30 degrees: projected, diag(3, 0) rotated.
  const double        c = std::cos(M_PI / 6), s = std::sin(M_PI / 6);
  std::vector<double> m = {3 * c * c - 2 * s * s, (3 + 2) * c * s,
                           (3 + 2) * c * s, 3 * s * s - 2 * c * c};
  project_to_positive_semidefinite(m, 2);
  EXPECT_NEAR(m[0], 3 * c * c, 1e-12);
  EXPECT_NEAR(m[1], 3 * c * s, 1e-12);
  EXPECT_NEAR(m[3], 3 * s * s, 1e-12);
  // A positive definite matrix is left alone.
  std::vector<double> spd = {2, 1, 0, 1, 2, 1, 0, 1, 2}, copy = spd;
  project_to_positive_semidefinite(spd, 3);
  for (unsigned int i = 0; i < 9; ++i)
    EXPECT_EQ(spd[i], copy[i]);
}

TEST(ContactCCD, PointFallingOnATriangleStopsShortOfTheOffset)
{
  // A point 1 above the triangle moves down by 3: it would reach the
  // offset 0.2 at t = 0.8 / 3. ACCD stops before, keeping a tenth of the
  // gap, and at the returned time the distance is above the offset.
  const Points4 x{Point<3>(0.2, 0.2, 1), Point<3>(0, 0, 0), Point<3>(1, 0, 0),
                  Point<3>(0, 1, 0)};
  const Displacements dx{Tensor<1, 3>({0, 0, -3}), Tensor<1, 3>(),
                         Tensor<1, 3>(), Tensor<1, 3>()};
  const double t = additive_ccd(PrimitivePair::point_triangle, x, dx, 0.2);
  EXPECT_LE(t, 0.8 / 3);
  EXPECT_GE(t, 0.7 / 3);
  EXPECT_GT(1 - 3 * t, 0.2);
  // Moving away or sideways out of reach: the whole step.
  Displacements away = dx;
  away[0]            = Tensor<1, 3>({0, 0, 2});
  EXPECT_EQ(additive_ccd(PrimitivePair::point_triangle, x, away, 0.2), 1.0);
  // Already within the offset: no motion at all.
  Points4 inside = x;
  inside[0][2]   = 0.1;
  EXPECT_EQ(additive_ccd(PrimitivePair::point_triangle, inside, dx, 0.2), 0.0);
}

TEST(ContactCCD, TriangleSweptThroughAPointIsCaught)
{
  // The triangle moves up through a fixed point (a moving obstacle): the
  // relative motion matters, not which side moves.
  const Points4 x{Point<3>(0.2, 0.2, 1), Point<3>(0, 0, 0), Point<3>(1, 0, 0),
                  Point<3>(0, 1, 0)};
  const Tensor<1, 3>  up({0, 0, 3});
  const Displacements dx{Tensor<1, 3>(), up, up, up};
  const double t = additive_ccd(PrimitivePair::point_triangle, x, dx, 0.2);
  EXPECT_LE(t, 0.8 / 3);
  EXPECT_GE(t, 0.7 / 3);
  // Edges crossing: two segments 1 apart closing by 2.
  const Points4 edges{Point<3>(-1, 0, 0), Point<3>(1, 0, 0), Point<3>(0, -1, 1),
                      Point<3>(0, 1, 1)};
  const Displacements down{Tensor<1, 3>(), Tensor<1, 3>(),
                           Tensor<1, 3>({0, 0, -2}), Tensor<1, 3>({0, 0, -2})};
  const double        t_edges =
      additive_ccd(PrimitivePair::segment_segment, edges, down, 0.1);
  EXPECT_LE(t_edges, 0.45);
  EXPECT_GE(t_edges, 0.4);
}

TEST(ContactCCD, SlidingAtATinyGapStridesButStaysConservative)
{
  // A point a hair above the offset slides 1 along a big triangle. The
  // plain walk would take steps of about the gap over the slide, 1e-9,
  // and give up at its iteration limit; the separating plane proves the
  // whole slide safe.
  const double        offset = 0.2, hair = 1e-9;
  const Points4       x{Point<3>(-1, -1, offset + hair), Point<3>(-5, -5, 0),
                  Point<3>(5, -5, 0), Point<3>(-5, 5, 0)};
  const Displacements slide{Tensor<1, 3>({1, 0.5, 0}), Tensor<1, 3>(),
                            Tensor<1, 3>(), Tensor<1, 3>()};
  EXPECT_EQ(additive_ccd(PrimitivePair::point_triangle, x, slide, offset), 1.0);
  // The same slide sinking by 1.8e-6 from 1e-6 above the offset: it
  // reaches the offset at t = 1/1.8 and must stop before, at a distance
  // still above the offset.
  Points4 above         = x;
  above[0][2]           = offset + 1e-6;
  Displacements sinking = slide;
  sinking[0][2]         = -1.8e-6;
  const double t =
      additive_ccd(PrimitivePair::point_triangle, above, sinking, offset);
  EXPECT_LE(t, 1 / 1.8);
  EXPECT_GT(t, 0.9 * 0.9 / 1.8); // strides most of the way, not 1e-6
  EXPECT_GT(above[0][2] + t * sinking[0][2], offset);
  // Two crossing edges, one sliding along itself a hair above the other.
  const Points4       edges{Point<3>(-1, 0, 0), Point<3>(1, 0, 0),
                      Point<3>(0, -1, 0.1 + hair), Point<3>(0, 1, 0.1 + hair)};
  const Tensor<1, 3>  along({0, 0.5, 0});
  const Displacements slide_edges{Tensor<1, 3>(), Tensor<1, 3>(), along, along};
  EXPECT_EQ(
      additive_ccd(PrimitivePair::segment_segment, edges, slide_edges, 0.1),
      1.0);
}
