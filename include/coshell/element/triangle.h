#pragma once

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <array>
#include <stdexcept>
#include <string>

namespace coshell::element
{
  using dealii::Point;
  using dealii::Tensor;

  /// Vertex coordinates of a triangle in its own plane (the element frame).
  using PlanarTriangle = std::array<Point<2>, 3>;
  /// Vertex coordinates of a triangle in space.
  using SpatialTriangle = std::array<Point<3>, 3>;

  /// Thrown for a triangle whose area is (numerically) zero.
  class DegenerateTriangle : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };

  /// Signed area, positive for counter-clockwise vertices.
  double signed_area(const PlanarTriangle &triangle);

  /// Area of a triangle in space.
  double area(const SpatialTriangle &triangle);

  /// Gradients of the barycentric coordinates L_0, L_1, L_2 (the linear
  /// shape functions), valid for either vertex orientation. Throws
  /// DegenerateTriangle under the same criterion as make_element_frame.
  std::array<Tensor<1, 2>, 3>
  barycentric_gradients(const PlanarTriangle &triangle);

  /// Orthonormal element frame: e1 along edge 0->1 (the paper's edge AB),
  /// e3 = normalised (x1-x0) x (x2-x0), e2 = e3 x e1, origin at vertex 0.
  /// With these axes the planar vertices are always counter-clockwise.
  struct ElementFrame
  {
    Point<3>                    origin;
    std::array<Tensor<1, 3>, 3> axes;   ///< e1, e2, e3
    PlanarTriangle              planar; ///< vertex coordinates in (e1, e2)
  };

  /// Builds the frame. Throws DegenerateTriangle when the area is below
  /// 1e-12 times the squared longest edge (or zero).
  ElementFrame make_element_frame(const SpatialTriangle &triangle);

  /// Expresses a global vector in the frame axes.
  Tensor<1, 3> to_local(const ElementFrame &frame, const Tensor<1, 3> &global);
} // namespace coshell::element
