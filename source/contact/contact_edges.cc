// Edge-edge pairs of the shell and the obstacles, and the pair energy
// common to every kind of pair (with the edge-edge mollifier of Li et
// al. 2020, section 4.3, for nearly parallel edges).

#include <coshell/contact/ccd.h>
#include <coshell/contact/contact.h>

#include <boost/iterator/function_output_iterator.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

namespace coshell::contact
{
  using namespace dealii;
  namespace bgi = boost::geometry::index;

  namespace
  {
    /// Below this fraction of |e0|^2 |e1|^2 (the squared sine of the
    /// angle between the edges, in their rest lengths) the mollifier
    /// fades an edge-edge pair out (IPC's 1e-3).
    constexpr double parallel_threshold = 1e-3;

    /// c = |e0 x e1|^2 = |e0|^2 |e1|^2 - (e0.e1)^2 with e0 = p1 - p0,
    /// e1 = q1 - q0, and its derivatives in the 12 coordinates.
    struct CrossSquared
    {
      double        value;
      Coordinates12 gradient{};
      Matrix12      hessian{};
    };

    CrossSquared cross_squared(const std::array<Point<3>, 4> &p)
    {
      const Tensor<1, 3> e0 = p[1] - p[0], e1 = p[3] - p[2];
      const double       aa = e0 * e0, bb = e1 * e1, ab = e0 * e1;
      CrossSquared       c{aa * bb - ab * ab};
      // d c / d e0 and d c / d e1, spread to the points (e = end - start).
      const Tensor<1, 3>                g0 = 2 * bb * e0 - 2 * ab * e1;
      const Tensor<1, 3>                g1 = 2 * aa * e1 - 2 * ab * e0;
      const std::array<double, 4>       sign{-1, 1, -1, 1};
      const std::array<unsigned int, 4> edge{0, 0, 1, 1};
      const std::array<Tensor<1, 3>, 2> g{g0, g1};
      for (unsigned int k = 0; k < 4; ++k)
        for (unsigned int i = 0; i < 3; ++i)
          c.gradient[3 * k + i] = sign[k] * g[edge[k]][i];
      // Second derivatives in (e0, e1), then spread the same way.
      const auto block =
          [&](unsigned int a, unsigned int b, unsigned int i, unsigned int j)
      {
        const double delta = i == j ? 1.0 : 0.0;
        if (a == 0 && b == 0)
          return 2 * bb * delta - 2 * e1[i] * e1[j];
        if (a == 1 && b == 1)
          return 2 * aa * delta - 2 * e0[i] * e0[j];
        // d2 c / d e0_i d e1_j, or its transpose.
        const Tensor<1, 3> &u = a == 0 ? e0 : e1, &v = a == 0 ? e1 : e0;
        return 4 * u[i] * v[j] - 2 * v[i] * u[j] - 2 * ab * delta;
      };
      for (unsigned int k = 0; k < 4; ++k)
        for (unsigned int l = 0; l < 4; ++l)
          for (unsigned int i = 0; i < 3; ++i)
            for (unsigned int j = 0; j < 3; ++j)
              c.hessian[3 * k + i][3 * l + j] =
                  sign[k] * sign[l] * block(edge[k], edge[l], i, j);
      return c;
    }
  } // namespace

  Contact::ShellCoordinates Contact::shell_coordinates(const Pair &pair)
  {
    if (pair.self)
      return {0, 12};
    if (pair.edge_edge)
      return {0, 6};
    return pair.shell_vertex_side ? ShellCoordinates{0, 3}
                                  : ShellCoordinates{3, 12};
  }

  bool Contact::on_obstacle(const Pair &pair, unsigned int k)
  {
    if (pair.self)
      return false;
    if (pair.edge_edge)
      return k >= 2;
    return pair.shell_vertex_side ? k > 0 : k == 0;
  }

  SquaredDistance Contact::pair_distance(const Pair                    &pair,
                                         const std::array<Point<3>, 4> &p,
                                         bool derivatives)
  {
    return pair.edge_edge
               ? segment_segment_distance(p[0], p[1], p[2], p[3], derivatives)
               : point_triangle_distance(p[0], p[1], p[2], p[3], derivatives);
  }

  /// E = w m phi(g), g = sqrt(s) - offset: dg = ds / (2d),
  /// d2g = d2s / (2d) - ds ds^T / (4 d^3); with the mollifier m(c) =
  /// (c / eps)(2 - c / eps) below eps (1 above),
  /// grad E = w (m phi' dg + phi dm),
  /// hess E = w (m (phi'' dg dg^T + phi' d2g) + phi' (dg dm^T + dm dg^T)
  ///          + phi d2m).
  Contact::PairEnergy
  Contact::pair_energy(const Pair                    &pair,
                       const std::array<Point<3>, 4> &points,
                       const SquaredDistance         &s,
                       double                         weight,
                       const ScalarDerivatives       &phi,
                       bool                           with_hessian) const
  {
    const double  distance = std::sqrt(s.value);
    Coordinates12 dg;
    for (unsigned int i = 0; i < 12; ++i)
      dg[i] = s.gradient[i] / (2 * distance);
    double       m = 1, dm_dc = 0, d2m_dc2 = 0;
    CrossSquared c{0};
    if (pair.edge_edge)
    {
      // An obstacle is rigid: its current edge length is its rest length.
      const double rest_other = pair.self
                                    ? shell_edge_length2_[pair.other]
                                    : (points[3] - points[2]).norm_square();
      const double eps =
          parallel_threshold * shell_edge_length2_[pair.shell] * rest_other;
      c = cross_squared(points);
      if (c.value < eps)
      {
        const double r = c.value / eps;
        m              = r * (2 - r);
        dm_dc          = 2 * (1 - r) / eps;
        d2m_dc2        = -2 / (eps * eps);
      }
    }
    PairEnergy energy;
    energy.value     = weight * m * phi.value;
    energy.mollifier = m;
    for (unsigned int i = 0; i < 12; ++i)
    {
      const double dm_i  = dm_dc * c.gradient[i];
      energy.gradient[i] = weight * (m * phi.first * dg[i] + phi.value * dm_i);
      for (unsigned int j = 0; j < 12 && with_hessian; ++j)
      {
        const double d2g = s.hessian[i][j] / (2 * distance) -
                           s.gradient[i] * s.gradient[j] /
                               (4 * distance * distance * distance);
        const double dm_j = dm_dc * c.gradient[j];
        const double d2m =
            d2m_dc2 * c.gradient[i] * c.gradient[j] + dm_dc * c.hessian[i][j];
        energy.hessian[i][j] =
            weight *
            (m * (phi.second * dg[i] * dg[j] + phi.first * d2g) +
             phi.first * (dg[i] * dm_j + dm_i * dg[j]) + phi.value * d2m);
      }
    }
    return energy;
  }

  void Contact::build_edges()
  {
    const auto &reference = model_.surface().get_vertices();
    std::map<std::array<unsigned, 2>, unsigned> index;
    shell_triangle_edges_.resize(shell_triangles_.size());
    for (unsigned int t = 0; t < shell_triangles_.size(); ++t)
      for (unsigned int k = 0; k < 3; ++k)
      {
        std::array<unsigned, 2> e{shell_triangles_[t][k],
                                  shell_triangles_[t][(k + 1) % 3]};
        std::sort(e.begin(), e.end());
        const auto [it, added] = index.emplace(e, shell_edges_.size());
        if (added)
        {
          shell_edges_.push_back(e);
          shell_edge_area_.push_back(0);
          shell_edge_length2_.push_back(
              (reference[e[1]] - reference[e[0]]).norm_square());
        }
        shell_edge_area_[it->second] += shell_triangle_area_[t] / 3;
        shell_triangle_edges_[t][k] = it->second;
      }
    for (const Obstacle &obstacle : parameters_.obstacles)
    {
      std::map<std::array<unsigned, 2>, unsigned> obstacle_index;
      auto &edges       = obstacle_edges_.emplace_back();
      auto &of_triangle = obstacle_triangle_edges_.emplace_back();
      for (const auto &t : obstacle.triangles)
      {
        auto &three = of_triangle.emplace_back();
        for (unsigned int k = 0; k < 3; ++k)
        {
          std::array<unsigned, 2> e{t[k], t[(k + 1) % 3]};
          std::sort(e.begin(), e.end());
          const auto [it, added] = obstacle_index.emplace(e, edges.size());
          if (added)
            edges.push_back(e);
          three[k] = it->second;
        }
      }
    }
  }

  void Contact::edges_near(
      const Tree                                 &tree,
      const std::vector<std::array<unsigned, 3>> &triangle_edges,
      EdgeMarks                                  &marks,
      std::initializer_list<Point<3>>             corners,
      double                                      inflation,
      std::vector<unsigned int>                  &edges)
  {
    edges.clear();
    // Neighbouring triangles share edges: take each once, without a sort
    // (which cost more than the query itself). The hits are taken as the
    // tree finds them, not gathered in a vector first, which would be
    // allocated anew for each of the many queries a haptic step makes.
    ++marks.query;
    const auto take_edges = [&](const std::pair<BoundingBox<3>, unsigned> &hit)
    {
      for (const unsigned f : triangle_edges[hit.second])
        if (marks.last[f] != marks.query)
        {
          marks.last[f] = marks.query;
          edges.push_back(f);
        }
    };
    tree.query(bgi::intersects(box_of(corners, inflation)),
               boost::make_function_output_iterator(take_edges));
  }

  double Contact::edge_offset(unsigned int obstacle, unsigned int e) const
  {
    return 0.5 * (offset(obstacle, true, shell_edges_[e][0]) +
                  offset(obstacle, true, shell_edges_[e][1]));
  }

} // namespace coshell::contact
