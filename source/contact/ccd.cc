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
    }
    return t; // the gap keeps shrinking slowly: stop where it is safe
  }
} // namespace coshell::contact
