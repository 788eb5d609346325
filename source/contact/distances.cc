#include <coshell/contact/distances.h>

#include <algorithm>

namespace coshell::contact
{
  using dealii::Tensor;

  namespace
  {
    using Points4 = std::array<Point<3>, 4>;
    using Weights = std::array<double, 4>;

    /// The squared distance |r|^2 of r = sum_i w_i x_i, where the weights
    /// are affine in m parameters (w = w0 + sum_k theta_k D_k) and theta
    /// minimises |r|^2. By the envelope theorem ds/dx_i = 2 w_i r; the
    /// Hessian adds to 2 w_i w_j I the change of the minimiser,
    /// -F A^-1 F^T with A = d2s/dtheta2 and F = d2s/dx dtheta.
    template<unsigned int m>
    SquaredDistance envelope(const Points4                &x,
                             const Weights                &w,
                             const std::array<Weights, m> &directions,
                             const std::array<double, 2>  &parameters,
                             bool                          derivatives)
    {
      SquaredDistance result;
      result.parameters = parameters;
      Tensor<1, 3> r;
      for (unsigned int i = 0; i < 4; ++i)
        r += w[i] * x[i];
      result.value = r * r;
      if (!derivatives)
        return result;
      for (unsigned int i = 0; i < 4; ++i)
        for (unsigned int c = 0; c < 3; ++c)
        {
          result.gradient[3 * i + c] = 2 * w[i] * r[c];
          for (unsigned int j = 0; j < 4; ++j)
            result.hessian[3 * i + c][3 * j + c] = 2 * w[i] * w[j];
        }
      if constexpr (m > 0)
      {
        std::array<Tensor<1, 3>, m> g; // dr/dtheta_k
        for (unsigned int k = 0; k < m; ++k)
          for (unsigned int j = 0; j < 4; ++j)
            g[k] += directions[k][j] * x[j];
        std::array<std::array<double, m>, m> a_inverse;
        if constexpr (m == 1)
          a_inverse[0][0] = 1 / (2 * (g[0] * g[0]));
        else
        {
          const double a00 = 2 * (g[0] * g[0]), a11 = 2 * (g[1] * g[1]),
                       a01 = 2 * (g[0] * g[1]);
          const double det = a00 * a11 - a01 * a01;
          a_inverse = {{{a11 / det, -a01 / det}, {-a01 / det, a00 / det}}};
        }
        std::array<std::array<double, m>, 12> f;
        for (unsigned int i = 0; i < 4; ++i)
          for (unsigned int c = 0; c < 3; ++c)
            for (unsigned int k = 0; k < m; ++k)
              f[3 * i + c][k] =
                  2 * directions[k][i] * r[c] + 2 * w[i] * g[k][c];
        for (unsigned int p = 0; p < 12; ++p)
          for (unsigned int q = 0; q < 12; ++q)
            for (unsigned int k = 0; k < m; ++k)
              for (unsigned int l = 0; l < m; ++l)
                result.hessian[p][q] -= f[p][k] * a_inverse[k][l] * f[q][l];
      }
      return result;
    }

    /// Point (index 0) to the segment of points i, j at parameter t.
    SquaredDistance to_edge(const Points4               &x,
                            unsigned int                 i,
                            unsigned int                 j,
                            double                       t,
                            const std::array<double, 2> &parameters,
                            bool                         derivatives)
    {
      Weights w{1, 0, 0, 0}, direction{0, 0, 0, 0};
      w[i]         = -(1 - t);
      w[j]         = -t;
      direction[i] = 1;
      direction[j] = -1;
      return envelope<1>(x, w, {direction}, parameters, derivatives);
    }

    SquaredDistance to_vertex(const Points4               &x,
                              unsigned int                 i,
                              const std::array<double, 2> &parameters,
                              bool                         derivatives)
    {
      Weights w{1, 0, 0, 0};
      w[i] = -1;
      return envelope<0>(x, w, {}, parameters, derivatives);
    }

    /// Point (index 0) to the segment of points i, j, end points included.
    /// The reported parameters are not meaningful here (degenerate case).
    SquaredDistance to_segment(const Points4 &x,
                               unsigned int   i,
                               unsigned int   j,
                               bool           derivatives)
    {
      const Tensor<1, 3> edge   = x[j] - x[i];
      const double       length = edge * edge;
      const double       t      = length > 0
                                      ? std::clamp((x[0] - x[i]) * edge / length, 0.0, 1.0)
                                      : 0.0;
      if (t <= 0)
        return to_vertex(x, i, {0, 0}, derivatives);
      if (t >= 1)
        return to_vertex(x, j, {0, 0}, derivatives);
      return to_edge(x, i, j, t, {0, 0}, derivatives);
    }

    SquaredDistance with_feature(SquaredDistance distance, unsigned int feature)
    {
      distance.feature = feature;
      return distance;
    }
  } // namespace

  // Region tests of the closest point on a triangle as in Ericson,
  // Real-Time Collision Detection (2005), section 5.1.5.
  SquaredDistance point_triangle_distance(const Point<3> &p,
                                          const Point<3> &a,
                                          const Point<3> &b,
                                          const Point<3> &c,
                                          bool            derivatives)
  {
    const Points4      x{p, a, b, c};
    const Tensor<1, 3> ab = b - a, ac = c - a;
    const double       d1 = ab * (p - a), d2 = ac * (p - a);
    if (d1 <= 0 && d2 <= 0)
      return with_feature(to_vertex(x, 1, {0, 0}, derivatives), 0);
    const double d3 = ab * (p - b), d4 = ac * (p - b);
    if (d3 >= 0 && d4 <= d3)
      return with_feature(to_vertex(x, 2, {1, 0}, derivatives), 1);
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0)
    {
      const double t = d1 / (d1 - d3);
      return with_feature(to_edge(x, 1, 2, t, {t, 0}, derivatives), 3);
    }
    const double d5 = ab * (p - c), d6 = ac * (p - c);
    if (d6 >= 0 && d5 <= d6)
      return with_feature(to_vertex(x, 3, {0, 1}, derivatives), 2);
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0)
    {
      const double t = d2 / (d2 - d6);
      return with_feature(to_edge(x, 1, 3, t, {0, t}, derivatives), 4);
    }
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0)
    {
      const double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
      return with_feature(to_edge(x, 2, 3, t, {1 - t, t}, derivatives), 5);
    }
    const double sum = va + vb + vc;
    if (!(sum > 0)) // degenerate triangle: the nearest of its edges
    {
      const std::array<std::array<unsigned int, 2>, 3> edges{
          {{1, 2}, {1, 3}, {2, 3}}};
      unsigned int best       = 0;
      double       best_value = 0;
      for (unsigned int k = 0; k < 3; ++k)
      {
        const double value =
            to_segment(x, edges[k][0], edges[k][1], false).value;
        if (k == 0 || value < best_value)
          best = k, best_value = value;
      }
      return to_segment(x, edges[best][0], edges[best][1], derivatives);
    }
    const double v = vb / sum, w = vc / sum;
    return envelope<2>(x, {1, -(1 - v - w), -v, -w},
                       {Weights{0, 1, -1, 0}, Weights{0, 1, 0, -1}}, {v, w},
                       derivatives);
  }

  // Closest points of two segments as in Ericson (2005), section 5.1.9,
  // with near-parallel segments measured from an end of the first.
  SquaredDistance segment_segment_distance(const Point<3> &p0,
                                           const Point<3> &p1,
                                           const Point<3> &q0,
                                           const Point<3> &q1,
                                           bool            derivatives)
  {
    const Points4      x{p0, p1, q0, q1};
    const Tensor<1, 3> d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
    const double       a = d1 * d1, e = d2 * d2, f = d2 * r;
    const double       tiny = 1e-300;
    double             s = 0, t = 0;
    if (a > tiny && e > tiny)
    {
      const double b = d1 * d2, c = d1 * r, denominator = a * e - b * b;
      s = denominator > 1e-12 * a * e
              ? std::clamp((b * f - c * e) / denominator, 0.0, 1.0)
              : 0.0;
      t = (b * s + f) / e;
      if (t < 0)
        t = 0, s = std::clamp(-c / a, 0.0, 1.0);
      else if (t > 1)
        t = 1, s = std::clamp((b - c) / a, 0.0, 1.0);
      if (denominator <= 1e-12 * a * e && t > 0 && t < 1)
        s = 0; // parallel: keep the end point, t free
    }
    else if (e > tiny)
      t = std::clamp(f / e, 0.0, 1.0);
    else if (a > tiny)
      s = std::clamp(-(d1 * r) / a, 0.0, 1.0);
    const bool    s_free = s > 0 && s<1, t_free = t> 0 && t < 1;
    const Weights w{1 - s, s, -(1 - t), -t};
    const Weights along_s{-1, 1, 0, 0}, along_t{0, 0, 1, -1};
    if (s_free && t_free)
      return envelope<2>(x, w, {along_s, along_t}, {s, t}, derivatives);
    if (s_free)
      return envelope<1>(x, w, {along_s}, {s, t}, derivatives);
    if (t_free)
      return envelope<1>(x, w, {along_t}, {s, t}, derivatives);
    return envelope<0>(x, w, {}, {s, t}, derivatives);
  }
} // namespace coshell::contact
