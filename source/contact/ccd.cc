#include <coshell/contact/ccd.h>
#include <coshell/contact/distances.h>

#include <algorithm>
#include <cmath>

namespace coshell::contact
{
  using dealii::Tensor;

  double primitive_distance(PrimitivePair pair, const Points4 &x)
  {
    const SquaredDistance s =
        pair == PrimitivePair::point_triangle
            ? point_triangle_distance(x[0], x[1], x[2], x[3], false)
            : segment_segment_distance(x[0], x[1], x[2], x[3], false);
    return std::sqrt(s.value);
  }

  namespace
  {
    /// The unit vector from the second primitive's closest point to the
    /// first's. The plane normal to it separates the two convex
    /// primitives by exactly their distance.
    Tensor<1, 3> separating_direction(PrimitivePair pair, const Points4 &x)
    {
      const bool            point = pair == PrimitivePair::point_triangle;
      const SquaredDistance s =
          point ? point_triangle_distance(x[0], x[1], x[2], x[3], true)
                : segment_segment_distance(x[0], x[1], x[2], x[3], true);
      // ds/dx of the first primitive's points sums to 2 r.
      Tensor<1, 3> r;
      for (unsigned int i = 0; i < (point ? 1u : 2u); ++i)
        for (unsigned int c = 0; c < 3; ++c)
          r[c] += 0.5 * s.gradient[3 * i + c];
      const double length = r.norm();
      return length > 0 ? r / length : r;
    }

    /// How far along the rest of the motion, x + tau dx with tau in
    /// [0, remaining], the plane that separates the primitives at x, held
    /// fixed in space, keeps them at least 'separation' apart. The
    /// distance of a point of one primitive to a point of the other along
    /// the plane's normal is linear in tau, so the largest such tau is the
    /// first root among the point pairs.
    double separated_advance(PrimitivePair        pair,
                             const Points4       &x,
                             const Displacements &dx,
                             double               remaining,
                             double               separation)
    {
      const Tensor<1, 3> n = separating_direction(pair, x);
      if (n.norm() == 0)
        return 0;
      const unsigned int split = pair == PrimitivePair::point_triangle ? 1 : 2;
      double             tau   = remaining;
      for (unsigned int i = 0; i < split; ++i)
        for (unsigned int j = split; j < 4; ++j)
        {
          const double apart = n * (x[i] - x[j]) - separation;
          const double rate  = n * (dx[i] - dx[j]);
          if (apart < 0)
            return 0;
          if (rate < 0)
            tau = std::min(tau, apart / -rate);
        }
      return tau;
    }

    /// Whether the walk of additive_ccd() should try the separating plane
    /// at this iteration: every 8th, so the walks of a few steps (nearly
    /// all of them) never pay for it.
    bool try_separating_plane(unsigned int iteration)
    {
      return iteration > 0 && iteration % 8 == 0;
    }
  } // namespace

  double additive_ccd(PrimitivePair        pair,
                      const Points4       &x_start,
                      const Displacements &dx_start,
                      double               minimum_distance,
                      double               kept_fraction)
  {
    // Only relative motion matters: remove the mean displacement, which
    // shrinks the bound on how fast the distance can change.
    Displacements dx   = dx_start;
    Tensor<1, 3>  mean = 0.25 * (dx[0] + dx[1] + dx[2] + dx[3]);
    for (auto &d : dx)
      d -= mean;
    const auto norm = [&](unsigned int i) { return dx[i].norm(); };
    // Upper bound of d(distance)/dt along the trajectories.
    const double rate =
        pair == PrimitivePair::point_triangle
            ? norm(0) + std::max({norm(1), norm(2), norm(3)})
            : std::max(norm(0), norm(1)) + std::max(norm(2), norm(3));
    Points4      x        = x_start;
    const double xi       = minimum_distance;
    double       distance = primitive_distance(pair, x);
    if (!(distance > xi))
      return 0;
    if (rate == 0)
      return 1;
    // The gap (d^2 - xi^2) / (d + xi) = d - xi, written as the paper
    // does to keep its relative accuracy when d is close to xi.
    const auto   gap = [xi](double d) { return (d * d - xi * xi) / (d + xi); };
    const double target = kept_fraction * gap(distance);
    double       t      = 0;
    double       step   = (1 - kept_fraction) * gap(distance) / rate;
    // The gap shrinks at most at 'rate': a first safe step past the end
    // means the whole motion is safe (the loop would find the same after
    // one more distance).
    if (step >= 1)
      return 1;
    for (unsigned int iteration = 0; iteration < 100000; ++iteration)
    {
      for (unsigned int i = 0; i < 4; ++i)
        x[i] += step * dx[i];
      distance = primitive_distance(pair, x);
      if (t > 0 && gap(distance) < target)
        return t;
      t += step;
      if (t >= 1)
        return 1;
      step = 0.9 * gap(distance) / rate;
      // A pair that slides along at a tiny gap takes ever shorter steps
      // (the gap over the relative displacement, which the sliding
      // dominates). The separating plane lets such a walk stride: often
      // over the whole rest of the motion. A stride short of that stops
      // at 0.9 of the way to where the plane's bound reaches the kept
      // gap, as the walk's own steps do: landing on the bound would leave
      // round-off to decide whether the walk stops there, and a run's
      // path (serial against MPI) with it.
      if (try_separating_plane(iteration))
      {
        const double plane_step =
            separated_advance(pair, x, dx, 1 - t, xi + target);
        if (plane_step >= 1 - t)
          return 1;
        step = std::max(step, 0.9 * plane_step);
      }
    }
    return t; // the gap keeps shrinking slowly: stop where it is safe
  }
} // namespace coshell::contact
