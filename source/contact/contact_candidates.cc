// The broad phase of contact: lists of candidate pairs that the pair search
// and the step filter share, kept while the shell and the obstacles move
// less than a margin, and screened by the distance each pair had when
// listed. Between two rebuilds no R-tree is queried and no pair far from
// contact has its distance or its CCD evaluated.
//
// Why the lists may be kept: a pair listed at positions x0 had a distance
// d0; after each side's points moved at most s and b from x0, the
// distance of the pair is at least d0 - s - b (the distance of a point to
// a triangle, or of two segments, is 1-Lipschitz in each point). A pair
// not listed had d0 >= reach + margin, so it stays out of reach while
// s + b <= margin, also along a straight motion whose two ends are within
// s and b of x0 (the distance of a point to x0 is convex along it).

#include <coshell/contact/ccd.h>
#include <coshell/contact/contact.h>
#include <coshell/contact/distances.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <numeric>

namespace coshell::contact
{
  using namespace dealii;
  namespace bgi = boost::geometry::index;

  namespace
  {
    using Hits = std::vector<std::pair<BoundingBox<3>, unsigned>>;

    /// The items (triangles or edges) a self-contact search row must skip,
    /// marked with the row they belong to. Marking a row's sorted
    /// exclusion list once is cheaper than a binary search per hit: a
    /// vertex's box of reach overlaps much of its own excluded
    /// neighbourhood, some (t/h)^2 triangles, and on a fine lens those
    /// searches show in a fold's profile (doc/performance/contact.md).
    class ExclusionMarks
    {
    public:
      explicit ExclusionMarks(std::size_t n_items)
          : row_of_(n_items, numbers::invalid_unsigned_int)
      {
      }
      void mark(unsigned int row, const std::vector<unsigned int> &excluded)
      {
        for (const unsigned int item : excluded)
          row_of_[item] = row;
      }
      bool excludes(unsigned int row, unsigned int item) const
      {
        return row_of_[item] == row;
      }

    private:
      std::vector<unsigned int> row_of_;
    };

    constexpr double unknown = -std::numeric_limits<double>::infinity();

    /// A pair's distance for its list, if 'measure'.
    double listed(bool measure, PrimitivePair type, const Points4 &points)
    {
      return measure ? primitive_distance(type, points) : unknown;
    }

    /// Whether two boxes overlap (touching counts).
    bool overlap(const BoundingBox<3> &a, const BoundingBox<3> &b)
    {
      for (unsigned int d = 0; d < 3; ++d)
        if (a.upper_bound(d) < b.lower_bound(d) ||
            b.upper_bound(d) < a.lower_bound(d))
          return false;
      return true;
    }

    /// Whether the boxes swept by the pair's two primitives (the point or
    /// first segment, then the rest), the first inflated by 'offset',
    /// meet; if not, the pair cannot come within its offset.
    bool swept_boxes_meet(PrimitivePair        type,
                          const Points4       &x,
                          const Displacements &dx,
                          double               offset)
    {
      const unsigned int split = type == PrimitivePair::point_triangle ? 1 : 2;
      std::array<Point<3>, 2> lower{x[0], x[split]}, upper = lower;
      for (unsigned int i = 0; i < 4; ++i)
        for (const Point<3> &p : {x[i], x[i] + dx[i]})
          for (unsigned int d = 0; d < 3; ++d)
          {
            lower[i >= split][d] = std::min(lower[i >= split][d], p[d]);
            upper[i >= split][d] = std::max(upper[i >= split][d], p[d]);
          }
      for (unsigned int d = 0; d < 3; ++d)
        if (upper[0][d] + offset < lower[1][d] ||
            upper[1][d] < lower[0][d] - offset)
          return false;
      return true;
    }

    Tensor<1, 3> along(const std::vector<Tensor<1, 3>> *d, unsigned int i)
    {
      return d ? (*d)[i] : Tensor<1, 3>();
    }

    /// largest = max(largest, value), except that a NaN stays: std::max
    /// drops it, and a drift or a clock that forgot a non-finite position
    /// (a diverged correction) would let the screens skip pairs wrongly.
    /// A NaN drift skips nothing (every screen compares false).
    void keep_largest(double &largest, double value)
    {
      largest = value > largest || std::isnan(value) ? value : largest;
    }

    /// The largest distance of the points (moved by d, if given) from
    /// 'listed', at the start and at the end of the motion.
    double largest_drift(const std::vector<unsigned int> *used,
                         const std::vector<Point<3>>     &x,
                         const std::vector<Tensor<1, 3>> *d,
                         const std::vector<Point<3>>     &listed)
    {
      double     largest = 0;
      const auto visit   = [&](unsigned int i)
      {
        keep_largest(largest, (x[i] - listed[i]).norm_square());
        if (d)
          keep_largest(largest, (x[i] + (*d)[i] - listed[i]).norm_square());
      };
      if (used)
        for (const unsigned int i : *used)
          visit(i);
      else
        for (unsigned int i = 0; i < x.size(); ++i)
          visit(i);
      return std::sqrt(largest);
    }

    /// The longest move of any point in the motion, shell or obstacle.
    double largest_motion(const std::vector<Tensor<1, 3>> *dx,
                          const std::vector<Tensor<1, 3>> *dX)
    {
      double largest = 0;
      for (const auto *moves : {dx, dX})
        if (moves)
          for (const Tensor<1, 3> &move : *moves)
            largest = std::max(largest, move.norm_square());
      return std::sqrt(largest);
    }

    /// As largest_drift(), less a common translation of all the points:
    /// their largest distance from the centre of the drifts' bounding box,
    /// at the start and at the end of the motion. Distances between shell
    /// primitives change by at most twice it (a translation changes none;
    /// the translations at the two ends, interpolated, bound the motion).
    double largest_relative_drift(const std::vector<unsigned int> &used,
                                  const std::vector<Point<3>>     &x,
                                  const std::vector<Tensor<1, 3>> *d,
                                  const std::vector<Point<3>>     &listed)
    {
      double largest = 0;
      if (used.empty())
        return largest;
      for (const bool end : {false, true})
      {
        if (end && !d)
          break;
        const auto drift = [&](unsigned int i)
        { return x[i] - listed[i] + (end ? (*d)[i] : Tensor<1, 3>()); };
        Tensor<1, 3> lower = drift(used.front()), upper = lower;
        for (const unsigned int i : used)
        {
          const Tensor<1, 3> moved = drift(i);
          for (unsigned int c = 0; c < 3; ++c)
          {
            lower[c] = std::min(lower[c], moved[c]);
            upper[c] = std::max(upper[c], moved[c]);
          }
        }
        const Tensor<1, 3> centre = 0.5 * (lower + upper);
        for (const unsigned int i : used)
          keep_largest(largest, (drift(i) - centre).norm_square());
      }
      return std::sqrt(largest);
    }

  } // namespace

  void Contact::CandidateRows::clear()
  {
    start.assign(1, 0);
    other.clear();
    distance.clear();
    nearest.clear();
    thickest.clear();
    anchored.clear();
    thickest_of_open_row = 0;
  }

  void Contact::CandidateRows::add(unsigned int primitive,
                                   double       listed,
                                   double       kept)
  {
    other.push_back(primitive);
    distance.push_back(listed);
    thickest_of_open_row = std::max(thickest_of_open_row, kept);
  }

  void Contact::CandidateRows::end_row()
  {
    const unsigned int first = start.back(), n = other.size() - first;
    // Kept per thread: the lists are made a row at a time, a vertex's or
    // an edge's, and three allocations a row showed in the profile.
    thread_local std::vector<unsigned int> order, row_other;
    thread_local std::vector<double>       row_distance;
    order.resize(n);
    std::iota(order.begin(), order.end(), 0u);
    std::sort(order.begin(), order.end(),
              [&](unsigned a, unsigned b)
              { return other[first + a] < other[first + b]; });
    row_other.assign(other.begin() + first, other.end());
    row_distance.assign(distance.begin() + first, distance.end());
    for (unsigned int k = 0; k < n; ++k)
    {
      other[first + k]    = row_other[order[k]];
      distance[first + k] = row_distance[order[k]];
    }
    nearest.push_back(std::accumulate(row_distance.begin(), row_distance.end(),
                                      std::numeric_limits<double>::infinity(),
                                      [](double a, double b)
                                      { return std::min(a, b); }));
    thickest.push_back(thickest_of_open_row);
    thickest_of_open_row = 0;
    start.push_back(other.size());
    anchored.resize(other.size(), -std::numeric_limits<double>::infinity());
  }

  bool Contact::Screen::skips_search(double listed, double reach) const
  {
    return listed - shift >= reach;
  }

  bool Contact::Screen::skips_anchored(double anchored, double reach) const
  {
    // The margin, a part in 10^9 of the reach, stands for the round-off
    // of the distances and of the clock: a pair this skips would have
    // been found at or beyond its reach, so the search keeps the same
    // pairs to the bit.
    return anchored - clock > reach * (1 + 1e-9);
  }

  bool Contact::Screen::clears(double listed, double offset) const
  {
    // skips_filter() with every pair's largest move bounded by the
    // motion's: clears() implies skips_filter(), to the bit.
    const double gap = listed - shift - offset;
    return gap > 0 && 0.8 * gap > 4 * largest_move;
  }

  bool Contact::Screen::skips_filter(double               listed,
                                     double               offset,
                                     const Displacements &moves) const
  {
    // additive_ccd() returns 1 at once when the gap exceeds its rate
    // bound over (1 - kept fraction) = 0.9; 0.8 leaves room for
    // round-off. That bound, |dx_0 - m| + max |dx_i - m| with m the mean
    // move, is at most 4 max |dx_k|.
    const double gap = listed - shift - offset;
    if (!(gap > 0))
      return false;
    double largest = 0;
    for (const auto &move : moves)
      largest = std::max(largest, move.norm_square());
    return 0.8 * gap > 4 * std::sqrt(largest);
  }

  double Contact::candidate_margin() const
  {
    // A quarter of the thickness: on the IOL push the filter and the
    // search take least with it among 0.1, 0.25, 0.5 and 1 times the
    // thickness (wider lists cost more to screen than their rebuilds
    // save; doc/performance/contact.md).
    return 0.25 * largest_thickness_;
  }

  /// Whether candidates_ covers the motion, and if so the screens of its
  /// pairs: per obstacle, and for self contact.
  bool Contact::covers(const Motion        &motion,
                       std::vector<Screen> &obstacle_screens,
                       Screen              &self_screen) const
  {
    const Candidates &c = candidates_;
    if (c.margin < 0)
      return false;
    // A thickening since the lists were made brings pairs within reach as
    // a move would: it counts as drift on both sides.
    const double growth = offset_growth_since(c.stretches);
    const double shell_now =
        largest_drift(&shell_vertices_, motion.x, nullptr, c.shell) + growth;
    const double shell_swept =
        largest_drift(&shell_vertices_, motion.x, motion.dx, c.shell) + growth;
    if (parameters_.self_contact)
    {
      // A lens pushed along the injector mostly translates: its self
      // distances stay, and the lists with them.
      const double self_swept =
          largest_relative_drift(shell_vertices_, motion.x, motion.dx, c.shell);
      if (2 * self_swept + growth > c.margin)
        return false;
      self_screen = {2 * largest_relative_drift(shell_vertices_, motion.x,
                                                nullptr, c.shell) +
                     growth};
    }
    else
      self_screen = {2 * shell_now};
    obstacle_screens.resize(current_.size());
    for (unsigned int o = 0; o < current_.size(); ++o)
    {
      const auto *dX = o == motion.moving ? motion.dX : nullptr;
      // Positions the lists saw, to the bit: no drift.
      const bool   unmoved = c.obstacle_stamps[o] == obstacle_moves_[o];
      const double now     = unmoved ? 0
                                     : largest_drift(nullptr, current_[o], nullptr,
                                                     c.obstacles[o]);
      const double swept =
          dX ? largest_drift(nullptr, current_[o], dX, c.obstacles[o]) : now;
      if (shell_swept + swept > c.margin)
        return false;
      obstacle_screens[o] = {shell_now + now};
    }
    return true;
  }

  /// The lists of obstacle o for the motion, as far as 'margin' beyond
  /// each pair's reach; with their distances at the motion's start if
  /// 'measure'. 'shell_tree': the shell triangles' boxes, swept by dx.
  void Contact::make_obstacle_candidates(unsigned int  o,
                                         const Motion &motion,
                                         const Tree   &shell_tree,
                                         double        margin,
                                         bool          measure,
                                         Candidates   &c) const
  {
    const auto &x         = motion.x;
    const auto *dx        = motion.dx;
    const auto *dX        = o == motion.moving ? motion.dX : nullptr;
    const auto &X         = current_[o];
    const auto &triangles = parameters_.obstacles[o].triangles;
    Tree        swept_obstacle;
    if (dX)
      swept_obstacle = obstacle_triangle_tree(o, dX);
    const Tree &obstacle_tree = dX ? swept_obstacle : this->obstacle_tree(o);
    Hits        hits;
    auto       &vertex_triangle = c.vertex_triangle[o];
    vertex_triangle.clear();
    for (const unsigned v : shell_vertices_)
    {
      hits.clear();
      obstacle_tree.query(
          bgi::intersects(box_of({x[v], x[v] + along(dx, v)},
                                 pair_reach(offset(o, true, v)) + margin)),
          std::back_inserter(hits));
      for (const auto &hit : hits)
      {
        const auto &t = triangles[hit.second];
        vertex_triangle.add(hit.second,
                            listed(measure, PrimitivePair::point_triangle,
                                   {{x[v], X[t[0]], X[t[1]], X[t[2]]}}),
                            offset(o, true, v));
      }
      vertex_triangle.end_row();
    }
    // Only the obstacle's vertices near the (swept) shell can meet it.
    BoundingBox<3> shell_box = swept_shell_box(x, dx);
    shell_box.extend(margin);
    auto &triangle_vertex = c.triangle_vertex[o];
    triangle_vertex.clear();
    for (unsigned int j = 0; j < X.size(); ++j)
    {
      const BoundingBox<3> box =
          box_of({X[j], X[j] + along(dX, j)}, reach(o) + margin);
      hits.clear();
      if (overlap(box, shell_box))
        shell_tree.query(bgi::intersects(box), std::back_inserter(hits));
      for (const auto &hit : hits)
      {
        const auto &t = shell_triangles_[hit.second];
        triangle_vertex.add(hit.second,
                            listed(measure, PrimitivePair::point_triangle,
                                   {{X[j], x[t[0]], x[t[1]], x[t[2]]}}),
                            offset(o, false, hit.second));
      }
      triangle_vertex.end_row();
    }
    if (parameters_.edge_edge_pairs)
      make_edge_candidates(o, motion, obstacle_tree, margin, measure, c);
  }

  void Contact::make_edge_candidates(unsigned int  o,
                                     const Motion &motion,
                                     const Tree   &obstacle_tree,
                                     double        margin,
                                     bool          measure,
                                     Candidates   &c) const
  {
    const auto               &x  = motion.x;
    const auto               *dx = motion.dx;
    const auto               &X  = current_[o];
    std::vector<unsigned int> edges;
    EdgeMarks                 marks(obstacle_edges_[o].size());
    auto                     &rows = c.edge_edge[o];
    rows.clear();
    for (unsigned int e = 0; e < shell_edges_.size(); ++e)
    {
      const auto [a, b] = shell_edges_[e];
      edges_near(obstacle_tree, obstacle_triangle_edges_[o], marks,
                 {x[a], x[b], x[a] + along(dx, a), x[b] + along(dx, b)},
                 pair_reach(edge_offset(o, e)) + margin, edges);
      for (const unsigned f : edges)
      {
        const auto [p, q] = obstacle_edges_[o][f];
        rows.add(f,
                 listed(measure, PrimitivePair::segment_segment,
                        {{x[a], x[b], X[p], X[q]}}),
                 edge_offset(o, e));
      }
      rows.end_row();
    }
  }

  /// Self contact's lists: shell vertices against the shell triangles
  /// they may pair with, and shell edges e against edges f > e.
  void Contact::make_self_candidates(const Motion &motion,
                                     const Tree   &shell_tree,
                                     double        margin,
                                     bool          measure,
                                     Candidates   &c) const
  {
    const auto    &x          = motion.x;
    const auto    *dx         = motion.dx;
    const double   activation = pair_potential_->activation_distance();
    Hits           hits;
    ExclusionMarks excluded_triangles(shell_triangles_.size());
    auto          &vertex_triangle = c.self_vertex_triangle;
    vertex_triangle.clear();
    for (const unsigned v : shell_vertices_)
    {
      excluded_triangles.mark(v, excluded_[v]);
      hits.clear();
      shell_tree.query(
          bgi::intersects(box_of({x[v], x[v] + along(dx, v)},
                                 self_reach(v, activation) + margin)),
          std::back_inserter(hits));
      for (const auto &hit : hits)
      {
        if (excluded_triangles.excludes(v, hit.second))
          continue;
        const auto &t = shell_triangles_[hit.second];
        vertex_triangle.add(hit.second,
                            listed(measure, PrimitivePair::point_triangle,
                                   {{x[v], x[t[0]], x[t[1]], x[t[2]]}}),
                            self_offset(v, hit.second));
      }
      vertex_triangle.end_row();
    }
    c.self_edge_edge.clear();
    if (!parameters_.edge_edge_pairs)
      return;
    std::vector<unsigned int> edges;
    EdgeMarks                 marks(shell_edges_.size());
    ExclusionMarks            excluded_edges(shell_edges_.size());
    for (unsigned int e = 0; e < shell_edges_.size(); ++e)
    {
      const auto [a, b] = shell_edges_[e];
      excluded_edges.mark(e, excluded_edges_[e]);
      edges_near(shell_tree, shell_triangle_edges_, marks,
                 {x[a], x[b], x[a] + along(dx, a), x[b] + along(dx, b)},
                 self_edge_reach(e, activation) + margin, edges);
      for (const unsigned f : edges)
      {
        if (f <= e || excluded_edges.excludes(e, f))
          continue;
        const auto [p, q] = shell_edges_[f];
        c.self_edge_edge.add(f,
                             listed(measure, PrimitivePair::segment_segment,
                                    {{x[a], x[b], x[p], x[q]}}),
                             self_edge_offset(e, f));
      }
      c.self_edge_edge.end_row();
    }
  }

  /// Makes candidates_ anew at the shell's positions x and the obstacles'
  /// present ones unless they still cover them; returns the screens.
  void Contact::update_candidates(const std::vector<Point<3>> &x,
                                  std::vector<Screen>         &obstacle_screens,
                                  Screen                      &self_screen)
  {
    const Motion still{x, nullptr, invalid_obstacle, nullptr};
    if (covers(still, obstacle_screens, self_screen))
      return;
    Candidates &c        = candidates_;
    c.margin             = candidate_margin();
    c.stretches          = stretch_;
    c.shell              = x;
    c.obstacles          = current_;
    c.searched_shell     = x;
    c.searched_obstacles = current_;
    c.obstacle_stamps.resize(current_.size());
    for (unsigned int o = 0; o < current_.size(); ++o)
      c.obstacle_stamps[o] = obstacle_stamp(o);
    c.searched_stamps = c.obstacle_stamps;
    c.shell_travel    = 0;
    c.self_travel     = 0;
    c.obstacle_travel.assign(current_.size(), 0);
    c.vertex_triangle.resize(current_.size());
    c.triangle_vertex.resize(current_.size());
    c.edge_edge.resize(current_.size());
    const Tree shell_tree = shell_triangle_tree(x, nullptr, 0);
    for (unsigned int o = 0; o < current_.size(); ++o)
      make_obstacle_candidates(o, still, shell_tree, c.margin, true, c);
    if (parameters_.self_contact)
      make_self_candidates(still, shell_tree, c.margin, true, c);
    obstacle_screens.assign(current_.size(), Screen());
    self_screen = Screen();
  }

  /// Between two searches every point of a pair's primitives moves by at
  /// most the longest move of its side's vertices (the primitives are
  /// convex hulls of them), so its distance changes by at most the two
  /// sides' longest moves added: an obstacle's travel and the shell's.
  /// Shell to shell, a common translation changes no distance, so self
  /// pairs count twice the longest move less it.
  void Contact::advance_search_clock(const std::vector<Point<3>> &x,
                                     std::vector<Screen> &obstacle_screens,
                                     Screen              &self_screen)
  {
    // A non-finite position makes a travel NaN (keep_largest), and the
    // clock then skips nothing until the lists are made anew.
    Candidates &c = candidates_;
    c.shell_travel +=
        largest_drift(&shell_vertices_, x, nullptr, c.searched_shell);
    if (parameters_.self_contact)
      c.self_travel += 2 * largest_relative_drift(shell_vertices_, x, nullptr,
                                                  c.searched_shell);
    c.searched_shell = x;
    for (unsigned int o = 0; o < current_.size(); ++o)
    {
      if (c.searched_stamps[o] != obstacle_moves_[o])
      {
        const double move = largest_drift(nullptr, current_[o], nullptr,
                                          c.searched_obstacles[o]);
        if (move > 0)
        {
          c.obstacle_travel[o] += move;
          c.searched_obstacles[o] = current_[o];
        }
        // A finite move saw finite positions (a NaN stays in the drift).
        c.searched_stamps[o] = std::isfinite(move) ? obstacle_moves_[o] : 0;
      }
      obstacle_screens[o].clock = c.shell_travel + c.obstacle_travel[o];
    }
    self_screen.clock = c.self_travel;
  }

  /// Largest fraction of the motion that keeps every pair farther apart
  /// than its offset: additive CCD on the listed pairs the screens do
  /// not clear. The lists are candidates_ if they cover the motion, else
  /// made for it alone (the shell's triangles and the moving obstacle
  /// swept), for obstacle 'only' if given, else for all.
  double Contact::filter_fraction(const Motion &motion, unsigned int only) const
  {
    std::vector<Screen> obstacle_screens;
    Screen              self_screen;
    const bool          cached = covers(motion, obstacle_screens, self_screen);
    Candidates          swept;
    if (!cached)
    {
      obstacle_screens.assign(current_.size(), Screen());
      swept.vertex_triangle.resize(current_.size());
      swept.triangle_vertex.resize(current_.size());
      swept.edge_edge.resize(current_.size());
      const Tree shell_tree = shell_triangle_tree(motion.x, motion.dx, 0);
      for (unsigned int o = 0; o < current_.size(); ++o)
        if (only == invalid_obstacle || o == only)
          make_obstacle_candidates(o, motion, shell_tree, 0, false, swept);
      if (parameters_.self_contact && only == invalid_obstacle)
        make_self_candidates(motion, shell_tree, 0, false, swept);
    }
    const double largest_move = largest_motion(motion.dx, motion.dX);
    for (Screen &screen : obstacle_screens)
      screen.largest_move = largest_move;
    self_screen.largest_move   = largest_move;
    const Candidates &c        = cached ? candidates_ : swept;
    double            fraction = 1;
    for (unsigned int o = 0; o < current_.size(); ++o)
      if (only == invalid_obstacle || o == only)
        fraction = std::min(fraction, obstacle_filter_fraction(
                                          motion, o, c, obstacle_screens[o]));
    if (parameters_.self_contact && only == invalid_obstacle)
      fraction =
          std::min(fraction, self_filter_fraction(motion, c, self_screen));
    return fraction;
  }

  bool Contact::out_of_reach(const Screen        &screen,
                             const CandidateRows &rows,
                             unsigned int         row) const
  {
    return screen.skips_search(rows.nearest[row],
                               pair_reach(rows.thickest[row]));
  }

  bool Contact::clears_row(const Screen        &screen,
                           const CandidateRows &rows,
                           unsigned int         row) const
  {
    return screen.clears(rows.nearest[row],
                         pair_potential_->filter_offset(rows.thickest[row]));
  }

  /// The fraction one listed pair allows. Only pairs whose swept boxes
  /// come within their offset reach additive_ccd(), which also stops a
  /// pair closing 90 % of a larger gap: the set it sees is then the same
  /// whatever lists it came from. The penalty's filter keeps only a
  /// fraction of the offset.
  double Contact::pair_filter_fraction(const Screen        &screen,
                                       double               listed,
                                       PrimitivePair        type,
                                       const Points4       &points,
                                       const Displacements &moves,
                                       double               kept) const
  {
    const double offset = pair_potential_->filter_offset(kept);
    if (screen.skips_filter(listed, offset, moves) ||
        !swept_boxes_meet(type, points, moves, offset))
      return 1;
    return additive_ccd(type, points, moves, offset);
  }

  double Contact::obstacle_filter_fraction(const Motion     &motion,
                                           unsigned int      o,
                                           const Candidates &c,
                                           const Screen     &screen) const
  {
    const auto &x               = motion.x;
    const auto *dx              = motion.dx;
    const auto *dX              = o == motion.moving ? motion.dX : nullptr;
    const auto &X               = current_[o];
    const auto &triangles       = parameters_.obstacles[o].triangles;
    const auto &vertex_triangle = c.vertex_triangle[o];
    double      fraction        = 1;
    for (unsigned int k = 0; k < shell_vertices_.size(); ++k)
    {
      if (clears_row(screen, vertex_triangle, k))
        continue;
      const unsigned v = shell_vertices_[k];
      for (unsigned i = vertex_triangle.start[k];
           i < vertex_triangle.start[k + 1]; ++i)
      {
        const double kept = offset(o, true, v);
        if (screen.clears(vertex_triangle.distance[i],
                          pair_potential_->filter_offset(kept)))
          continue;
        const auto &t = triangles[vertex_triangle.other[i]];
        fraction      = std::min(
                 fraction, pair_filter_fraction(screen, vertex_triangle.distance[i],
                                                PrimitivePair::point_triangle,
                                                {{x[v], X[t[0]], X[t[1]], X[t[2]]}},
                                                {{along(dx, v), along(dX, t[0]),
                                                  along(dX, t[1]), along(dX, t[2])}},
                                                kept));
      }
    }
    const auto &triangle_vertex = c.triangle_vertex[o];
    for (unsigned int j = 0; j < X.size(); ++j)
    {
      if (clears_row(screen, triangle_vertex, j))
        continue;
      for (unsigned i = triangle_vertex.start[j];
           i < triangle_vertex.start[j + 1]; ++i)
      {
        const unsigned triangle = triangle_vertex.other[i];
        const double   kept     = offset(o, false, triangle);
        if (screen.clears(triangle_vertex.distance[i],
                          pair_potential_->filter_offset(kept)))
          continue;
        const auto &t = shell_triangles_[triangle];
        fraction      = std::min(
                 fraction, pair_filter_fraction(screen, triangle_vertex.distance[i],
                                                PrimitivePair::point_triangle,
                                                {{X[j], x[t[0]], x[t[1]], x[t[2]]}},
                                                {{along(dX, j), along(dx, t[0]),
                                                  along(dx, t[1]), along(dx, t[2])}},
                                                kept));
      }
    }
    if (parameters_.edge_edge_pairs)
      fraction = std::min(fraction, edge_filter_fraction(motion, o, c, screen));
    return fraction;
  }

  double Contact::edge_filter_fraction(const Motion     &motion,
                                       unsigned int      o,
                                       const Candidates &c,
                                       const Screen     &screen) const
  {
    const auto &x        = motion.x;
    const auto *dx       = motion.dx;
    const auto *dX       = o == motion.moving ? motion.dX : nullptr;
    const auto &X        = current_[o];
    const auto &rows     = c.edge_edge[o];
    double      fraction = 1;
    for (unsigned int e = 0; e < shell_edges_.size(); ++e)
    {
      if (clears_row(screen, rows, e))
        continue;
      const auto [a, b]    = shell_edges_[e];
      const double kept    = edge_offset(o, e);
      const double cleared = pair_potential_->filter_offset(kept);
      for (unsigned i = rows.start[e]; i < rows.start[e + 1]; ++i)
      {
        if (screen.clears(rows.distance[i], cleared))
          continue;
        const auto [p, q] = obstacle_edges_[o][rows.other[i]];
        fraction          = std::min(
                     fraction,
                     pair_filter_fraction(
                         screen, rows.distance[i], PrimitivePair::segment_segment,
                         {{x[a], x[b], X[p], X[q]}},
                         {{along(dx, a), along(dx, b), along(dX, p), along(dX, q)}},
                         kept));
      }
    }
    return fraction;
  }

  double Contact::self_filter_fraction(const Motion     &motion,
                                       const Candidates &c,
                                       const Screen     &screen) const
  {
    const auto &x        = motion.x;
    const auto *dx       = motion.dx;
    double      fraction = 1;
    const auto  filter   = [&](double listed, PrimitivePair type,
                            const std::array<unsigned, 4> &ids, double kept)
    {
      if (screen.clears(listed, pair_potential_->filter_offset(kept)))
        return;
      fraction = std::min(
          fraction,
          pair_filter_fraction(screen, listed, type,
                               {{x[ids[0]], x[ids[1]], x[ids[2]], x[ids[3]]}},
                               {{along(dx, ids[0]), along(dx, ids[1]),
                                 along(dx, ids[2]), along(dx, ids[3])}},
                               kept));
    };
    const auto &vertex_triangle = c.self_vertex_triangle;
    for (unsigned int k = 0; k < shell_vertices_.size(); ++k)
    {
      if (clears_row(screen, vertex_triangle, k))
        continue;
      const unsigned v = shell_vertices_[k];
      for (unsigned i = vertex_triangle.start[k];
           i < vertex_triangle.start[k + 1]; ++i)
      {
        const unsigned triangle = vertex_triangle.other[i];
        const auto    &t        = shell_triangles_[triangle];
        filter(vertex_triangle.distance[i], PrimitivePair::point_triangle,
               {v, t[0], t[1], t[2]}, self_offset(v, triangle));
      }
    }
    const auto &edge_edge = c.self_edge_edge;
    for (unsigned int e = 0; e + 1 < edge_edge.start.size(); ++e)
    {
      if (clears_row(screen, edge_edge, e))
        continue;
      for (unsigned i = edge_edge.start[e]; i < edge_edge.start[e + 1]; ++i)
      {
        const unsigned f = edge_edge.other[i];
        filter(edge_edge.distance[i], PrimitivePair::segment_segment,
               {shell_edges_[e][0], shell_edges_[e][1], shell_edges_[f][0],
                shell_edges_[f][1]},
               self_edge_offset(e, f));
      }
    }
    return fraction;
  }

  std::uint64_t
  Contact::update_self_couplings(const model::ShellState &state) const
  {
    if (!parameters_.self_contact)
      return 0;
    // Pairs that may come within reach during the step: a margin of the
    // largest thickness (the candidate lists' own margin is too narrow
    // for the steps of a quasi-static roll-up). A pair that comes closer
    // still keeps its exact force; only its coupling to the other side
    // drops out of the tangent. While the shell's drift since the list
    // was made, less a common translation, stays below a quarter of the
    // margin, no pair came more than half the margin closer: a lens
    // pushed along a nozzle keeps its list, and the matrix its pattern.
    std::vector<Point<3>> x = shell_positions(state);
    if (coupling_positions_.empty() ||
        largest_relative_drift(shell_vertices_, x, nullptr,
                               coupling_positions_) > largest_thickness_ / 4)
    {
      // By distance, not by box: the boxes' corners and the triangles'
      // boxes took in far more pairs than the margin asks for.
      Candidates   c;
      const Motion still{x, nullptr, invalid_obstacle, nullptr};
      const double margin = largest_thickness_;
      make_self_candidates(still, shell_triangle_tree(x, nullptr, 0), margin,
                           true, c);
      coupling_pairs_.clear();
      const double activation      = pair_potential_->activation_distance();
      const auto  &vertex_triangle = c.self_vertex_triangle;
      for (unsigned int k = 0; k < shell_vertices_.size(); ++k)
        for (unsigned i = vertex_triangle.start[k];
             i < vertex_triangle.start[k + 1]; ++i)
        {
          const unsigned v = shell_vertices_[k], t = vertex_triangle.other[i];
          if (vertex_triangle.distance[i] <
              self_offset(v, t) + activation + margin)
            for (const unsigned w : shell_triangles_[t])
              coupling_pairs_.push_back({v, w});
        }
      const auto &edge_edge = c.self_edge_edge;
      for (unsigned int e = 0; e + 1 < edge_edge.start.size(); ++e)
        for (unsigned i = edge_edge.start[e]; i < edge_edge.start[e + 1]; ++i)
        {
          const unsigned f = edge_edge.other[i];
          if (edge_edge.distance[i] <
              self_edge_offset(e, f) + activation + margin)
            for (const unsigned v : shell_edges_[e])
              for (const unsigned w : shell_edges_[f])
                coupling_pairs_.push_back({v, w});
        }
      coupling_positions_ = std::move(x);
      // Unique in the process: a problem that outlives this contact (or
      // gathers from two) cannot take a new list for one it has seen.
      static std::atomic<std::uint64_t> generations{0};
      coupling_generation_ = ++generations;
    }
    return coupling_generation_;
  }
} // namespace coshell::contact
