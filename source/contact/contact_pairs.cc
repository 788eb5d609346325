// Finding the contact pairs of the shell and the obstacles, and their
// forces and stiffness.

#include <coshell/base/stopwatch.h>
#include <coshell/contact/barrier.h>
#include <coshell/contact/contact.h>
#include <coshell/contact/distances.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace coshell::contact
{
  using namespace dealii;
  namespace bgi = boost::geometry::index;

  namespace
  {
    /// The (sorted) mesh vertices of a point-triangle feature code.
    std::array<long, 3> feature_vertices(const std::array<unsigned, 3> &t,
                                         unsigned int                   feature)
    {
      static const std::array<std::array<int, 3>, 7> corners = {{{0, -1, -1},
                                                                 {1, -1, -1},
                                                                 {2, -1, -1},
                                                                 {0, 1, -1},
                                                                 {0, 2, -1},
                                                                 {1, 2, -1},
                                                                 {0, 1, 2}}};
      std::array<long, 3>                            ids{-1, -1, -1};
      for (unsigned int i = 0; i < 3; ++i)
        if (corners[feature][i] >= 0)
          ids[i] = t[corners[feature][i]];
      std::sort(ids.begin(), ids.end());
      return ids;
    }
  } // namespace

  namespace
  {
    /// A pair found by the broad phase, with the closest features of its
    /// two sides (sorted mesh vertex ids, -1 padded) and its distance.
    struct Candidate
    {
      std::array<long, 3> shell, obstacle;
      double              distance;
      bool                shell_side_varies; ///< which side's feature varies
      /// False for a witness only (it takes part in the local minima, but
      /// is not listed as a pair).
      bool listed = true;
    };

    /// Whether feature a is a proper part (vertex, edge) of feature b.
    bool proper_part(const std::array<long, 3> &a, const std::array<long, 3> &b)
    {
      unsigned int shared = 0, size_a = 0, size_b = 0;
      for (const long id : a)
        if (id >= 0)
        {
          ++size_a;
          shared += std::count(b.begin(), b.end(), id);
        }
      for (const long id : b)
        size_b += id >= 0;
      return shared == size_a && size_a < size_b;
    }

    /// Keeps a candidate only where its gap is a local minimum over the
    /// surface: not if a feature it bounds has as small a gap or smaller
    /// (a vertex over the middle of a flat face is also within reach of
    /// the face's edges and of the neighbouring triangles' shared edge;
    /// only the face counts, so a frictionless plane pushes only along
    /// its normal). By gap, not distance: where triangles of different
    /// thickness meet, the nearer feature may keep the larger gap, and the
    /// candidate dropped must not be one the collision filter stops at
    /// while no listed pair pushes back.
    std::vector<bool> local_minima(const std::vector<Candidate> &candidates,
                                   const std::vector<double>    &gaps)
    {
      std::vector<bool> keep(candidates.size(), true);
      for (unsigned int i = 0; i < candidates.size(); ++i)
        for (unsigned int j = 0; j < candidates.size() && keep[i]; ++j)
        {
          const auto &a = candidates[i], &b = candidates[j];
          const auto &fa = a.shell_side_varies ? a.shell : a.obstacle;
          const auto &fb = b.shell_side_varies ? b.shell : b.obstacle;
          if (proper_part(fa, fb) && gaps[j] <= gaps[i])
            keep[i] = false;
        }
      return keep;
    }
  } // namespace

  /// Pairs within reach, one per pair of closest features (and, with
  /// Pairs = local minima, only the local minima of the distance).
  /// Gathers the candidates of one point (a shell vertex or an obstacle
  /// vertex) and keeps one pair per pair of closest features (and, with
  /// Pairs = local minima, only the local minima of the distance).
  class Contact::PairSelector
  {
  public:
    explicit PairSelector(Contact &contact) : contact_(contact) {}
    void add(const Candidate &candidate, const Pair &pair)
    {
      candidates_.push_back(candidate);
      found_.push_back(pair);
    }
    void settle()
    {
      const unsigned int n = candidates_.size();
      gaps_.resize(n);
      for (unsigned int k = 0; k < n; ++k)
        gaps_[k] = candidates_[k].distance - contact_.offset(found_[k]);
      // Assigned, not made anew: settle() runs once per point or edge.
      if (contact_.parameters_.local_minima_only)
        keep_ = local_minima(candidates_, gaps_);
      else
        keep_.assign(n, true);
      const std::vector<bool> &keep = keep_;
      for (unsigned int k = 0; k < n; ++k)
      {
        // Each settle() gathers the pairs of one point or edge, which is
        // part of the key: pairs of different calls never share a key.
        if (!keep[k] || !candidates_[k].listed || !smallest_of_its_key(k, keep))
          continue;
        contact_.pairs_.push_back(found_[k]);
        contact_.pairs_.back().searched_distance = candidates_[k].distance;
        contact_.smallest_gap_  = std::min(contact_.smallest_gap_, gaps_[k]);
        const unsigned int side = found_[k].self ? 0 : found_[k].obstacle + 1;
        double            &side_gap = contact_.smallest_gap_by_side_[side];
        side_gap                    = std::min(side_gap, gaps_[k]);
        contact_.largest_penetration_ =
            std::max(contact_.largest_penetration_, -gaps_[k]);
      }
      candidates_.clear();
      found_.clear();
    }

  private:
    /// Obstacle (-1: self), which side's vertex is the pair's point, and
    /// the closest features of both sides.
    using Key = std::array<long, 8>;
    Key key(unsigned int k) const
    {
      const auto &c = candidates_[k];
      const Pair &p = found_[k];
      return {p.self ? -1 : long(p.obstacle),
              long(p.shell_vertex_side),
              c.shell[0],
              c.shell[1],
              c.shell[2],
              c.obstacle[0],
              c.obstacle[1],
              c.obstacle[2]};
    }
    /// Of the kept candidates with the same closest features, whether k
    /// has the smallest gap (the first of equals): triangles of different
    /// thickness may share the feature. A point has a handful of
    /// candidates, so a scan beats a map.
    bool smallest_of_its_key(unsigned int             k,
                             const std::vector<bool> &keep) const
    {
      const Key own = key(k);
      for (unsigned int j = 0; j < candidates_.size(); ++j)
        if (j != k && keep[j] && candidates_[j].listed &&
            (gaps_[j] < gaps_[k] || (gaps_[j] == gaps_[k] && j < k)) &&
            key(j) == own)
          return false;
      return true;
    }

    Contact               &contact_;
    std::vector<Candidate> candidates_;
    std::vector<Pair>      found_;
    std::vector<double>    gaps_;
    std::vector<bool>      keep_;
  };

  void Contact::find_pairs(const std::vector<Point<3>> &x)
  {
    pairs_.clear();
    std::vector<Screen> screens;
    Screen              self_screen;
    update_candidates(x, screens, self_screen);
    advance_search_clock(x, screens, self_screen);
    PairSelector selector(*this);
    for (unsigned int o = 0; o < current_.size(); ++o)
    {
      find_shell_vertex_pairs(o, x, screens[o], selector);
      find_obstacle_vertex_pairs(o, x, screens[o], selector);
      if (parameters_.edge_edge_pairs)
        find_edge_pairs(o, x, screens[o], selector);
    }
    if (parameters_.self_contact)
      find_self_pairs(x, self_screen, selector);
    if (parameters_.self_contact && parameters_.edge_edge_pairs)
      find_self_edge_pairs(x, self_screen, selector);
  }

  void Contact::find_shell_vertex_pairs(unsigned int                 o,
                                        const std::vector<Point<3>> &x,
                                        const Screen                &screen,
                                        PairSelector                &selector)
  {
    const auto &X         = current_[o];
    const auto &triangles = parameters_.obstacles[o].triangles;
    auto       &rows      = candidates_.vertex_triangle[o];
    for (unsigned int k = 0; k < shell_vertices_.size(); ++k)
    {
      if (out_of_reach(screen, rows, k))
        continue;
      const unsigned v            = shell_vertices_[k];
      const double   vertex_reach = pair_reach(offset(o, true, v));
      for (unsigned i = rows.start[k]; i < rows.start[k + 1]; ++i)
      {
        if (screen.skips_search(rows.distance[i], vertex_reach) ||
            screen.skips_anchored(rows.anchored[i], vertex_reach))
          continue;
        const auto &t = triangles[rows.other[i]];
        const auto  d =
            point_triangle_distance(x[v], X[t[0]], X[t[1]], X[t[2]], false);
        const double distance = std::sqrt(d.value);
        rows.anchored[i]      = distance + screen.clock;
        if (distance < vertex_reach)
          selector.add({{-1, -1, long(v)},
                        feature_vertices(t, d.feature),
                        distance,
                        false},
                       {true, o, v, rows.other[i], shell_vertex_area_[v]});
      }
      selector.settle();
    }
  }

  void Contact::find_self_pairs(const std::vector<Point<3>> &x,
                                const Screen                &screen,
                                PairSelector                &selector)
  {
    const double activation = pair_potential_->activation_distance();
    auto        &rows       = candidates_.self_vertex_triangle;
    for (unsigned int k = 0; k < shell_vertices_.size(); ++k)
    {
      if (out_of_reach(screen, rows, k))
        continue;
      const unsigned v = shell_vertices_[k];
      for (unsigned i = rows.start[k]; i < rows.start[k + 1]; ++i)
      {
        const unsigned triangle = rows.other[i];
        const double   reach    = self_offset(v, triangle) + activation;
        if (screen.skips_search(rows.distance[i], reach) ||
            screen.skips_anchored(rows.anchored[i], reach))
          continue;
        const auto &t = shell_triangles_[triangle];
        const auto  d =
            point_triangle_distance(x[v], x[t[0]], x[t[1]], x[t[2]], false);
        const double distance = std::sqrt(d.value);
        rows.anchored[i]      = distance + screen.clock;
        if (distance < reach)
          selector.add({{-1, -1, long(v)},
                        feature_vertices(t, d.feature),
                        distance,
                        false},
                       {true, 0, v, triangle, shell_vertex_area_[v], true});
      }
      selector.settle();
    }
  }

  void Contact::find_obstacle_vertex_pairs(unsigned int                 o,
                                           const std::vector<Point<3>> &x,
                                           const Screen                &screen,
                                           PairSelector &selector)
  {
    const auto &X    = current_[o];
    auto       &rows = candidates_.triangle_vertex[o];
    for (unsigned int j = 0; j < X.size(); ++j)
    {
      // Each pair's reach is the obstacle's, not its own offset's; an
      // empty row's nearest is infinite.
      if (screen.skips_search(rows.nearest[j], reach(o)))
        continue;
      for (unsigned i = rows.start[j]; i < rows.start[j + 1]; ++i)
      {
        if (screen.skips_search(rows.distance[i], reach(o)) ||
            screen.skips_anchored(rows.anchored[i], reach(o)))
          continue;
        const unsigned triangle = rows.other[i];
        const auto    &t        = shell_triangles_[triangle];
        const auto     d =
            point_triangle_distance(X[j], x[t[0]], x[t[1]], x[t[2]], false);
        const double distance = std::sqrt(d.value);
        rows.anchored[i]      = distance + screen.clock;
        // A shell vertex against an obstacle vertex is also the shell
        // vertex search's pair, with the vertex's thickness (the mean of
        // its triangles'). Where this triangle keeps the larger offset it
        // binds first (the filter stops at it) and is listed too; else it
        // only witnesses for the local minima.
        const bool vertex_vertex =
            d.feature < 3 &&
            offset(o, false, triangle) <= offset(o, true, t[d.feature]);
        if (distance < reach(o))
          selector.add(
              {feature_vertices(t, d.feature),
               {-1, -1, long(j)},
               distance,
               true,
               !vertex_vertex},
              {false, o, triangle, j, shell_triangle_area_[triangle] / 3});
      }
      selector.settle();
    }
  }

  Contact::Tree
  Contact::shell_triangle_tree(const std::vector<Point<3>>     &x,
                               const std::vector<Tensor<1, 3>> *dx,
                               double                           inflation) const
  {
    std::vector<std::pair<BoundingBox<3>, unsigned>> boxes;
    boxes.reserve(shell_triangles_.size());
    std::vector<Point<3>> corners;
    for (unsigned int k = 0; k < shell_triangles_.size(); ++k)
    {
      corners.clear();
      for (const unsigned v : shell_triangles_[k])
      {
        corners.push_back(x[v]);
        if (dx)
          corners.push_back(x[v] + (*dx)[v]);
      }
      BoundingBox<3> box(corners);
      box.extend(inflation);
      boxes.emplace_back(box, k);
    }
    const base::Stopwatch watch(timing_.tree_build);
    return pack_rtree(boxes);
  }

  double Contact::max_reach() const
  {
    double largest = 0;
    for (unsigned int o = 0; o < current_.size(); ++o)
      largest = std::max(largest, reach(o));
    if (parameters_.self_contact)
      largest = std::max(largest, largest_current_thickness() +
                                      pair_potential_->activation_distance());
    return largest;
  }

  /// The four points of a pair (the point first) and where the shell's
  /// coordinates are among their 12: [0, 3) or [3, 12).
  std::array<Point<3>, 4>
  Contact::pair_points(const Pair                  &pair,
                       const std::vector<Point<3>> &x,
                       const std::vector<Point<3>> &X) const
  {
    if (pair.self && pair.edge_edge)
    {
      const auto &e = shell_edges_[pair.shell], &f = shell_edges_[pair.other];
      return {x[e[0]], x[e[1]], x[f[0]], x[f[1]]};
    }
    if (pair.self)
    {
      const auto &t = shell_triangles_[pair.other];
      return {x[pair.shell], x[t[0]], x[t[1]], x[t[2]]};
    }
    if (pair.edge_edge)
    {
      const auto &e = shell_edges_[pair.shell];
      const auto &f = obstacle_edges_[pair.obstacle][pair.other];
      return {x[e[0]], x[e[1]], X[f[0]], X[f[1]]};
    }
    if (pair.shell_vertex_side)
    {
      const auto &t =
          parameters_.obstacles[pair.obstacle].triangles[pair.other];
      return {x[pair.shell], X[t[0]], X[t[1]], X[t[2]]};
    }
    const auto &t = shell_triangles_[pair.shell];
    return {X[pair.other], x[t[0]], x[t[1]], x[t[2]]};
  }

  model::DofBlock &Contact::pair_dofs(const Pair &pair,
                                      PairBlocks &blocks) const
  {
    const unsigned int n_vertices =
        (shell_coordinates(pair).last - shell_coordinates(pair).first) / 3;
    model::DofBlock &block = blocks[n_vertices];
    block.dofs.resize(3 * n_vertices);
    for (unsigned int i = 0; i < n_vertices; ++i)
    {
      const unsigned v =
          pair.self && pair.edge_edge
              ? shell_edges_[i < 2 ? pair.shell : pair.other][i % 2]
          : pair.self
              ? (i == 0 ? pair.shell : shell_triangles_[pair.other][i - 1])
          : pair.edge_edge         ? shell_edges_[pair.shell][i]
          : pair.shell_vertex_side ? pair.shell
                                   : shell_triangles_[pair.shell][i];
      for (unsigned int c = 0; c < 3; ++c)
        block.dofs[3 * i + c] = model_.vertex_dofs(v)[c];
    }
    if (block.vector.size() != block.dofs.size())
    {
      block.vector.reinit(block.dofs.size());
      block.matrix.reinit(block.dofs.size(), block.dofs.size());
    }
    return block;
  }
} // namespace coshell::contact

namespace coshell::contact
{
  using namespace dealii;

  /// Resets what add_pair_terms() and add_friction_terms() accumulate over
  /// the pairs: the loads on the obstacles, the potential, the forces and
  /// the friction dissipation to zero, the gaps to infinity, and the
  /// normal forces friction takes from this evaluation to none.
  void Contact::reset_pair_records()
  {
    for (auto &load : loads_)
      load = ObstacleLoad();
    self_active_pairs_ = 0;
    potential_         = 0;
    vertex_force_      = 0;
    std::fill(potential_per_obstacle_.begin(), potential_per_obstacle_.end(),
              0.0);
    std::fill(friction_dissipation_per_obstacle_.begin(),
              friction_dissipation_per_obstacle_.end(), 0.0);
    friction_dissipation_ = 0;
    for (auto &force : shell_force_)
      force = 0;
    std::fill(vertex_gap_.begin(), vertex_gap_.end(),
              std::numeric_limits<double>::infinity());
    normal_forces_.clear();
  }

  bool Contact::beyond_reach(const Pair &pair) const
  {
    // Obstacle vertices are searched within the obstacle's reach (its
    // thickest offset); the pairs they list beyond their own triangle's
    // offset carry no force: most of the pairs on the IOL's haptic bed.
    // (The other kinds are searched within their own reach.) The margin (a
    // millionth of a part per thousand) covers the round-off between the
    // search's distance and the one made again below, so a pair this skips
    // would have come out of phi(gap) as exactly zero: the terms are the same
    // to the bit.
    return pair.searched_distance > pair_reach(offset(pair)) * (1 + 1e-9);
  }

  /// Energy w phi(g) of a pair, g = |d| - offset, w = stiffness * area:
  /// its gradient and Hessian by the chain rule through d = sqrt(s),
  /// dg = ds / (2d), d2g = d2s / (2d) - ds ds^T / (4 d^3).
  void Contact::add_pair_terms(const model::ShellState & /*state*/,
                               const model::BlockSink &sink,
                               bool                    with_tangent)
  {
    const auto start = std::chrono::steady_clock::now();
    reset_pair_records();
    slopes_at_last_evaluation_ = with_tangent;
    if (with_tangent)
      reset_force_slopes();
    PairBlocks blocks;
    for (const Pair &pair : pairs_)
    {
      if (beyond_reach(pair))
        continue;
      const auto   points   = pair_points(pair, positions_, other_side(pair));
      const auto   s        = pair_distance(pair, points, true);
      const double distance = std::sqrt(s.value);
      const double gap      = distance - offset(pair);
      const ScalarDerivatives phi = pair_potential_->of_gap(gap);
      if (phi.first == 0 && phi.second == 0)
        continue;
      const double weight = pair_potential_->stiffness(kappa_) * pair.area;
      // The tangent, and the anticipated obstacle move, need the Hessian.
      const PairEnergy energy =
          pair_energy(pair, points, s, weight, phi,
                      with_tangent || (pending_ && !pair.self));
      const auto       shell = shell_coordinates(pair);
      model::DofBlock &block = pair_dofs(pair, blocks);
      for (unsigned int i = shell.first; i < shell.last; ++i)
        block.vector[i - shell.first] = -energy.gradient[i]; // on the shell
      if (with_tangent)
        pair_hessian(energy, shell, block.matrix);
      if (with_tangent && follows_force(pair))
        add_force_slopes(pair, block.dofs, energy, points);
      record_pair(pair, points, energy.gradient, gap, block);
      potential_ += energy.value;
      if (!pair.self)
        potential_per_obstacle_[pair.obstacle] += energy.value;
      // |d E / d distance| is the normal force of the pair, which
      // friction will use in the next step.
      if (friction_coefficient(pair) > 0)
        normal_forces_.push_back(
            {pair, weight * energy.mollifier * std::abs(phi.first),
             s.parameters,
             closest_point_difference(pair.edge_edge, points, s.parameters)});
      if (pending_ && !pair.self)
        anticipate_obstacle(pair, energy, block);
      sink(block);
      if (!stretch_.empty())
        add_stretch_terms(pair, points, s, weight, phi, energy, block, sink,
                          with_tangent);
    }
    add_friction_terms(sink, with_tangent);
    timing_.pair_terms +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
            .count();
  }

  /// While an obstacle is held back short of its position, the shell's
  /// residual gets the linearized effect of the rest of the obstacle's
  /// move, -K_so dX (as an inhomogeneous constraint does in deal.II's
  /// step-44), so the next Newton correction already moves the shell out
  /// of the obstacle's way; the term vanishes once the obstacle is there.
  std::array<Tensor<1, 3>, 4>
  Contact::remaining_obstacle_moves(const Pair &pair) const
  {
    const unsigned int          o = pair.obstacle;
    std::array<Tensor<1, 3>, 4> remaining;
    const auto                 &triangles = parameters_.obstacles[o].triangles;
    for (unsigned int k = 0; k < 4; ++k)
    {
      if (!on_obstacle(pair, k))
        continue;
      const unsigned int v =
          pair.edge_edge           ? obstacle_edges_[o][pair.other][k - 2]
          : pair.shell_vertex_side ? triangles[pair.other][k - 1]
                                   : pair.other;
      remaining[k] = target_[o][v] - current_[o][v];
    }
    return remaining;
  }

  void Contact::anticipate_obstacle(const Pair       &pair,
                                    const PairEnergy &energy,
                                    model::DofBlock  &block) const
  {
    const auto remaining = remaining_obstacle_moves(pair);
    const auto shell     = shell_coordinates(pair);
    for (unsigned int i = shell.first; i < shell.last; ++i)
      for (unsigned int j = 0; j < 12; ++j)
        if (j < shell.first || j >= shell.last)
          block.vector[i - shell.first] -=
              energy.hessian[i][j] * remaining[j / 3][j % 3];
  }

  void Contact::pair_hessian(const PairEnergy   &energy,
                             ShellCoordinates    shell,
                             FullMatrix<double> &matrix) const
  {
    const unsigned int n = shell.last - shell.first, first = shell.first;
    // Kept between pairs: a fresh vector per pair showed in the profile.
    thread_local std::vector<double> h;
    h.resize(n * n);
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = 0; j < n; ++j)
        h[i * n + j] = energy.hessian[first + i][first + j];
    if ((parameters_.project_tangent || projecting_this_step_) &&
        !exact_tangent_)
      project_to_positive_semidefinite(h, n);
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = 0; j < n; ++j)
        matrix(i, j) = h[i * n + j];
  }

  /// The pair's force and moment on its obstacle (the gradient on the
  /// obstacle's coordinates, the force on the obstacle being its
  /// negative), and the vertex fields.
  void Contact::record_pair(const Pair                    &pair,
                            const std::array<Point<3>, 4> &points,
                            const Coordinates12           &gradient,
                            double                         gap,
                            const model::DofBlock         &block)
  {
    for (unsigned int k = 0; k < 4 && !pair.self; ++k)
    {
      if (!on_obstacle(pair, k))
        continue;
      ObstacleLoad      &load = loads_[pair.obstacle];
      const Tensor<1, 3> f(
          {-gradient[3 * k], -gradient[3 * k + 1], -gradient[3 * k + 2]});
      load.force += f;
      load.moment += cross_product_3d(points[k], f);
    }
    if (pair.self)
      ++self_active_pairs_;
    else
      ++loads_[pair.obstacle].active_pairs;
    add_shell_force(pair, block);
    const auto mark = [&](unsigned v)
    { vertex_gap_[v] = std::min(vertex_gap_[v], gap); };
    if (pair.edge_edge)
    {
      for (const unsigned v : shell_edges_[pair.shell])
        mark(v);
      if (pair.self)
        for (const unsigned v : shell_edges_[pair.other])
          mark(v);
      return;
    }
    if (pair.shell_vertex_side)
      mark(pair.shell);
    const unsigned int triangle = pair.self ? pair.other : pair.shell;
    if (pair.self || !pair.shell_vertex_side)
      for (const unsigned v : shell_triangles_[triangle])
        mark(v);
  }
} // namespace coshell::contact

namespace coshell::contact
{
  using namespace dealii;
  namespace bgi = boost::geometry::index;

  void Contact::find_edge_pairs(unsigned int                 o,
                                const std::vector<Point<3>> &x,
                                const Screen                &screen,
                                PairSelector                &selector)
  {
    const auto &X    = current_[o];
    auto       &rows = candidates_.edge_edge[o];
    for (unsigned int e = 0; e < shell_edges_.size(); ++e)
    {
      if (out_of_reach(screen, rows, e))
        continue;
      const auto [a, b]       = shell_edges_[e];
      const double edge_reach = pair_reach(edge_offset(o, e));
      for (unsigned i = rows.start[e]; i < rows.start[e + 1]; ++i)
      {
        if (screen.skips_search(rows.distance[i], edge_reach) ||
            screen.skips_anchored(rows.anchored[i], edge_reach))
          continue;
        const unsigned f  = rows.other[i];
        const auto [c, d] = obstacle_edges_[o][f];
        rows.anchored[i] =
            offer_edge_pair(selector, {true, o, e, f, shell_edge_area_[e]},
                            {x[a], x[b], X[c], X[d]}, {a, b, c, d},
                            edge_reach) +
            screen.clock;
      }
      selector.settle();
    }
  }
} // namespace coshell::contact

namespace coshell::contact
{
  using namespace dealii;

  double Contact::offer_edge_pair(PairSelector                  &selector,
                                  Pair                           pair,
                                  const std::array<Point<3>, 4> &p,
                                  const std::array<unsigned, 4> &ids,
                                  double                         reach) const
  {
    const double distance = std::sqrt(
        segment_segment_distance(p[0], p[1], p[2], p[3], false).value);
    if (distance >= reach)
      return distance;
    pair.edge_edge = true;
    selector.add({{-1, long(ids[0]), long(ids[1])},
                  {-1, long(ids[2]), long(ids[3])},
                  distance,
                  false},
                 pair);
    return distance;
  }

  /// Self contact of shell edges: each allowed pair (e, f), e < f, once.
  void Contact::find_self_edge_pairs(const std::vector<Point<3>> &x,
                                     const Screen                &screen,
                                     PairSelector                &selector)
  {
    const double activation = pair_potential_->activation_distance();
    auto        &rows       = candidates_.self_edge_edge;
    for (unsigned int e = 0; e < shell_edges_.size(); ++e)
    {
      if (out_of_reach(screen, rows, e))
        continue;
      const auto [a, b] = shell_edges_[e];
      for (unsigned i = rows.start[e]; i < rows.start[e + 1]; ++i)
      {
        const unsigned f     = rows.other[i];
        const double   reach = self_edge_offset(e, f) + activation;
        if (screen.skips_search(rows.distance[i], reach) ||
            screen.skips_anchored(rows.anchored[i], reach))
          continue;
        const auto [c, d] = shell_edges_[f];
        rows.anchored[i] =
            offer_edge_pair(selector,
                            {true, 0, e, f, shell_edge_area_[e], true},
                            {x[a], x[b], x[c], x[d]}, {a, b, c, d}, reach) +
            screen.clock;
      }
      selector.settle();
    }
  }
} // namespace coshell::contact
