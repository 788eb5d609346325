#pragma once

// Distances between the primitives of contact (a point and a triangle, two
// segments) with their first and second derivatives with respect to the
// 12 coordinates of the four points involved. Pure functions; no state.

#include <deal.II/base/point.h>

#include <array>

namespace coshell::contact
{
  using dealii::Point;
  using Coordinates12 = std::array<double, 12>;
  using Matrix12      = std::array<std::array<double, 12>, 12>;

  /// The squared distance s and, when asked for, ds/dx and d2s/dx2, with x
  /// the four points in the order the function takes them (3 * point +
  /// component).
  struct SquaredDistance
  {
    double        value = 0;
    Coordinates12 gradient{};
    Matrix12      hessian{};
    /// Parameters of the closest point on the second primitive (triangle:
    /// barycentric weights of vertices 1 and 2; segments: s on the first,
    /// t on the second), for friction and output.
    std::array<double, 2> parameters{};
    /// Point-triangle: the closest feature of the triangle, 0, 1, 2 its
    /// vertices a, b, c, 3 edge ab, 4 edge ac, 5 edge bc, 6 the face.
    unsigned int feature = 6;
  };

  /// Squared distance from point p to triangle (a, b, c), the closest
  /// point found by region tests (vertex, edge or face), with derivatives
  /// with respect to (p, a, b, c) when 'derivatives' is set. Degenerate
  /// triangles are measured as their edges.
  SquaredDistance point_triangle_distance(const Point<3> &p,
                                          const Point<3> &a,
                                          const Point<3> &b,
                                          const Point<3> &c,
                                          bool            derivatives);

  /// Squared distance between segments (p0, p1) and (q0, q1) with
  /// derivatives with respect to (p0, p1, q0, q1). For parallel segments
  /// the closest pair is not unique; one of them is measured through its
  /// end point, where the distance is still a smooth function nearby.
  SquaredDistance segment_segment_distance(const Point<3> &p0,
                                           const Point<3> &p1,
                                           const Point<3> &q0,
                                           const Point<3> &q1,
                                           bool            derivatives);
} // namespace coshell::contact
