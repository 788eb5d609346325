#include <coshell/element/triangle.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace coshell::element
{
  namespace
  {
    template<int dim>
    double longest_edge_squared(const std::array<Point<dim>, 3> &vertices)
    {
      return std::max({vertices[0].distance_square(vertices[1]),
                       vertices[1].distance_square(vertices[2]),
                       vertices[2].distance_square(vertices[0])});
    }

    // Scale-free test: a sliver is as useless as a point.
    template<int dim>
    void require_nondegenerate(const std::array<Point<dim>, 3> &vertices,
                               double                           area)
    {
      const double edge_squared = longest_edge_squared(vertices);
      if (!(area > 1e-12 * edge_squared))
      {
        std::ostringstream message;
        message << "degenerate triangle: area " << area
                << " is (numerically) zero for a longest edge of length "
                << std::sqrt(edge_squared) << " (vertices " << vertices[0]
                << "; " << vertices[1] << "; " << vertices[2] << ")";
        throw DegenerateTriangle(message.str());
      }
    }
  } // namespace

  double signed_area(const PlanarTriangle &triangle)
  {
    const Tensor<1, 2> a = triangle[1] - triangle[0];
    const Tensor<1, 2> b = triangle[2] - triangle[0];
    return 0.5 * (a[0] * b[1] - a[1] * b[0]);
  }

  double area(const SpatialTriangle &triangle)
  {
    return 0.5 * cross_product_3d(triangle[1] - triangle[0],
                                  triangle[2] - triangle[0])
                     .norm();
  }

  std::array<Tensor<1, 2>, 3>
  barycentric_gradients(const PlanarTriangle &triangle)
  {
    const double twice_area = 2.0 * signed_area(triangle);
    require_nondegenerate(triangle, std::abs(twice_area) / 2.0);

    // grad L_i = (y_j - y_k, x_k - x_j) / (2A) for cyclic (i, j, k).
    std::array<Tensor<1, 2>, 3> gradients;
    for (unsigned int i = 0; i < 3; ++i)
    {
      const Point<2> &pj = triangle[(i + 1) % 3];
      const Point<2> &pk = triangle[(i + 2) % 3];
      gradients[i][0]    = (pj[1] - pk[1]) / twice_area;
      gradients[i][1]    = (pk[0] - pj[0]) / twice_area;
    }
    return gradients;
  }

  ElementFrame make_element_frame(const SpatialTriangle &triangle)
  {
    const Tensor<1, 3> edge01 = triangle[1] - triangle[0];
    const Tensor<1, 3> normal =
        cross_product_3d(edge01, triangle[2] - triangle[0]);
    require_nondegenerate(triangle, 0.5 * normal.norm());

    ElementFrame frame;
    frame.origin  = triangle[0];
    frame.axes[0] = edge01 / edge01.norm();
    frame.axes[2] = normal / normal.norm();
    frame.axes[1] = cross_product_3d(frame.axes[2], frame.axes[0]);
    for (unsigned int i = 0; i < 3; ++i)
    {
      const Tensor<1, 3> offset = triangle[i] - frame.origin;
      frame.planar[i] =
          Point<2>(offset * frame.axes[0], offset * frame.axes[1]);
    }
    return frame;
  }

  Tensor<1, 3> to_local(const ElementFrame &frame, const Tensor<1, 3> &global)
  {
    Tensor<1, 3> local;
    for (unsigned int a = 0; a < 3; ++a)
      local[a] = global * frame.axes[a];
    return local;
  }
} // namespace coshell::element
