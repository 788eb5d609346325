#include <coshell/base/stopwatch.h>
#include <coshell/contact/barrier.h>
#include <coshell/contact/ccd.h>
#include <coshell/contact/contact.h>
#include <coshell/contact/distances.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <sstream>
#include <stdexcept>

namespace coshell::contact
{
  using namespace dealii;
  namespace bgi = boost::geometry::index;

  namespace
  {
    constexpr double infinity = std::numeric_limits<double>::infinity();

    Point<3> centroid(const std::vector<Point<3>> &points)
    {
      Point<3> sum;
      for (const auto &p : points)
        sum += p;
      return points.empty() ? sum : Point<3>(sum / double(points.size()));
    }
  } // namespace

  Contact::Contact(const model::ShellModel &model,
                   const ContactParameters &parameters,
                   double                   load_pressure)
      : model_(model), parameters_(parameters),
        largest_thickness_(model.thickness_range().second)
  {
    // Automatic scales: distances from the thinnest part of the shell,
    // stiffnesses from the mean thickness (the two agree when uniform).
    const auto  &material = model.element_parameters().material;
    const double thinnest = model.thickness_range().first;
    const double mean     = material.thickness;
    activation_           = parameters_.activation_distance > 0
                                ? parameters_.activation_distance
                                : 0.1 * thinnest;
    kappa_ = automatic_barrier_stiffness(material.youngs_modulus / mean,
                                         load_pressure);
    if (parameters_.penalty_stiffness <= 0)
      parameters_.penalty_stiffness = material.youngs_modulus / mean;
    if (parameters_.penalty_smoothing <= 0)
      parameters_.penalty_smoothing = 0.01 * thinnest;
    pair_potential_ = make_contact_potential(parameters_, activation_);

    const auto &vertices = model.surface().get_vertices();
    shell_vertex_area_.assign(vertices.size(), 0);
    for (const auto &cell : model.dof_handler().active_cell_iterators())
    {
      const std::array<unsigned, 3> t{
          cell->vertex_index(0), cell->vertex_index(1), cell->vertex_index(2)};
      const double area =
          0.5 * cross_product_3d(vertices[t[1]] - vertices[t[0]],
                                 vertices[t[2]] - vertices[t[0]])
                    .norm();
      shell_triangles_.push_back(t);
      shell_triangle_thickness_.push_back(model.material(cell).thickness);
      shell_triangle_area_.push_back(area);
      for (const unsigned v : t)
        shell_vertex_area_[v] += area / 3;
    }
    for (unsigned int v = 0; v < vertices.size(); ++v)
      if (model.vertex_is_used(v))
        shell_vertices_.push_back(v);
    const unsigned int n = parameters_.obstacles.size();
    current_.resize(n);
    target_.resize(n);
    obstacle_trees_.resize(n);
    obstacle_moves_.assign(n, 1);
    obstacle_friction_.resize(n);
    for (unsigned int o = 0; o < n; ++o)
      obstacle_friction_[o] = parameters_.obstacles[o].friction_coefficient;
    loads_.resize(n);
    obstacle_work_.assign(n, 0.0);
    potential_per_obstacle_.assign(n, 0.0);
    friction_dissipation_per_obstacle_.assign(n, 0.0);
    saved_potential_per_obstacle_.assign(n, 0.0);
    shell_force_.assign(n, Vector<double>(model.n_dofs()));
    saved_shell_force_ = shell_force_;
    // Only an interactive run's driven obstacles pay for their slopes,
    // unless follow_force_slopes() asks for every obstacle's.
    force_slopes_.resize(n);
    for (unsigned int o = 0; o < n; ++o)
      force_slopes_[o].followed = parameters_.obstacles[o].input != nullptr;
    for (const Obstacle &obstacle : parameters_.obstacles)
      start_centroids_.push_back(centroid(obstacle.positions(0)));
    vertex_gap_.assign(vertices.size(), infinity);
    build_edges();
    if (parameters_.self_contact)
      exclude_reference_neighbours();
    vertex_force_.reinit(model.n_dofs());
    forget_gaps();
  }

  double Contact::offset(unsigned int obstacle,
                         bool         shell_vertex_side,
                         unsigned int shell) const
  {
    const double thickness =
        shell_vertex_side ? vertex_thickness(shell) : triangle_thickness(shell);
    return 0.5 * thickness + parameters_.obstacles[obstacle].offset;
  }

  double Contact::offset(const Pair &pair) const
  {
    if (pair.edge_edge)
      return pair.self ? self_edge_offset(pair.shell, pair.other)
                       : edge_offset(pair.obstacle, pair.shell);
    return pair.self
               ? self_offset(pair.shell, pair.other)
               : offset(pair.obstacle, pair.shell_vertex_side, pair.shell);
  }

  double Contact::largest_offset(unsigned int obstacle) const
  {
    return 0.5 * largest_current_thickness() +
           parameters_.obstacles[obstacle].offset;
  }

  double Contact::reach(unsigned int obstacle) const
  {
    return largest_offset(obstacle) + pair_potential_->activation_distance();
  }

  std::vector<Point<3>>
  Contact::shell_positions(const model::ShellState &state) const
  {
    const auto           &reference = model_.surface().get_vertices();
    const auto           &values    = state.values();
    std::vector<Point<3>> x(reference);
    for (const unsigned v : shell_vertices_)
    {
      const auto &dofs = model_.vertex_dofs(v);
      for (unsigned int c = 0; c < 3; ++c)
        x[v][c] += values[dofs[c]];
    }
    return x;
  }

  BoundingBox<3> Contact::box_of(std::initializer_list<Point<3>> points,
                                 double                          inflation)
  {
    // Without the heap: these boxes are made in the innermost loops.
    Point<3> lower = *points.begin(), upper = lower;
    for (const Point<3> &p : points)
      for (unsigned int d = 0; d < 3; ++d)
      {
        lower[d] = std::min(lower[d], p[d]);
        upper[d] = std::max(upper[d], p[d]);
      }
    for (unsigned int d = 0; d < 3; ++d)
    {
      lower[d] -= inflation;
      upper[d] += inflation;
    }
    return BoundingBox<3>(std::make_pair(lower, upper));
  }

  BoundingBox<3>
  Contact::swept_shell_box(const std::vector<Point<3>>     &x,
                           const std::vector<Tensor<1, 3>> *dx) const
  {
    BoundingBox<3> box = box_of({x[shell_vertices_[0]]}, 0);
    for (const unsigned v : shell_vertices_)
    {
      box.merge_with(box_of({x[v]}, 0));
      if (dx)
        box.merge_with(box_of({x[v] + (*dx)[v]}, 0));
    }
    box.extend(max_reach()); // as far as any query box is inflated
    return box;
  }

  double Contact::pair_reach(double offset) const
  {
    return offset + pair_potential_->activation_distance();
  }

  void Contact::obstacle_moved(unsigned int obstacle)
  {
    obstacle_trees_[obstacle].reset();
    ++obstacle_moves_[obstacle];
  }

  std::uint64_t Contact::obstacle_stamp(unsigned int o) const
  {
    for (const Point<3> &p : current_[o])
      if (!std::isfinite(p.norm_square()))
        return 0;
    return obstacle_moves_[o];
  }

  const Contact::Tree &Contact::obstacle_tree(unsigned int o) const
  {
    if (!obstacle_trees_[o])
      obstacle_trees_[o] = obstacle_triangle_tree(o, nullptr);
    return *obstacle_trees_[o];
  }

  Contact::Tree
  Contact::obstacle_triangle_tree(unsigned int                     o,
                                  const std::vector<Tensor<1, 3>> *dX) const
  {
    const auto &X         = current_[o];
    const auto &triangles = parameters_.obstacles[o].triangles;
    std::vector<std::pair<BoundingBox<3>, unsigned>> boxes;
    boxes.reserve(triangles.size());
    const auto end = [&](unsigned int i)
    { return dX ? X[i] + (*dX)[i] : X[i]; };
    for (unsigned int k = 0; k < triangles.size(); ++k)
    {
      const auto &t = triangles[k];
      boxes.emplace_back(
          box_of({X[t[0]], X[t[1]], X[t[2]], end(t[0]), end(t[1]), end(t[2])},
                 0),
          k);
    }
    const base::Stopwatch watch(timing_.tree_build);
    return pack_rtree(boxes);
  }

  const std::vector<ObstacleLoad> &Contact::obstacle_loads() const
  {
    return loads_;
  }

  std::vector<double> Contact::obstacle_work() const
  {
    std::vector<double> work = obstacle_work_;
    for (unsigned int o = 0; o < work.size(); ++o)
      work[o] += step_work(o);
    return work;
  }

  double Contact::potential() const
  {
    return potential_;
  }

  Tensor<1, 3> Contact::obstacle_displacement(unsigned int o) const
  {
    return centroid(current_[o]) - start_centroids_[o];
  }

  const std::vector<Obstacle> &Contact::obstacles() const
  {
    return parameters_.obstacles;
  }

  double Contact::smallest_gap() const
  {
    return smallest_gap_;
  }

  double Contact::smallest_obstacle_gap(unsigned int o) const
  {
    return smallest_gap_by_side_[o + 1];
  }

  double Contact::smallest_self_gap() const
  {
    return smallest_gap_by_side_[0];
  }

  void Contact::forget_gaps()
  {
    smallest_gap_        = std::numeric_limits<double>::infinity();
    largest_penetration_ = 0;
    smallest_gap_by_side_.assign(parameters_.obstacles.size() + 1,
                                 smallest_gap_);
  }

  double Contact::largest_penetration() const
  {
    return largest_penetration_;
  }

  // kappa from a pressure scale p: as stiff as p / (d/2) at half the
  // activation distance d (material), or carrying p there (load).
  double Contact::automatic_barrier_stiffness(double stiffness_per_area,
                                              double load_pressure) const
  {
    if (parameters_.barrier_stiffness > 0)
      return parameters_.barrier_stiffness;
    const ScalarDerivatives b = log_barrier(0.5 * activation_, activation_);
    if (!parameters_.barrier_stiffness_from_load)
      return stiffness_per_area / b.second;
    if (!(load_pressure > 0))
      throw std::invalid_argument(
          "subsection Contact: Barrier stiffness scale = load needs a dead "
          "load (Loads: gravity, pressure, point or edge forces); this "
          "scene has none. Use material, or set Barrier stiffness");
    return load_pressure / std::abs(b.first);
  }

  double Contact::barrier_stiffness() const
  {
    return kappa_;
  }

  double Contact::activation_distance() const
  {
    return activation_;
  }

  bool Contact::obstacles_pending() const
  {
    return pending_;
  }
} // namespace coshell::contact

namespace coshell::contact
{
  using namespace dealii;
  namespace bgi = boost::geometry::index;

  using base::Stopwatch;

  double Contact::admissible_fraction(const model::ShellState &state,
                                      const Vector<double>    &correction) const
  {
    if (!pair_potential_->filters_steps())
      return 1;
    const Stopwatch             watch(timing_.filter);
    const std::vector<Point<3>> x = shell_positions(state);
    std::vector<Tensor<1, 3>>   dx(x.size());
    for (const unsigned v : shell_vertices_)
      for (unsigned int c = 0; c < 3; ++c)
        dx[v][c] = correction[model_.vertex_dofs(v)[c]];
    return std::min(
        filter_fraction({x, &dx, invalid_obstacle, nullptr}, invalid_obstacle),
        thickening_fraction(correction));
  }

  /// Moves each obstacle towards its position at the evaluation time, as
  /// far as the step filter allows against the shell as it is.
  void Contact::advance_obstacles(const std::vector<Point<3>> &x)
  {
    pending_ = false;
    for (unsigned int o = 0; o < current_.size(); ++o)
    {
      if (current_[o] == target_[o])
        continue;
      std::vector<Tensor<1, 3>> dX(current_[o].size());
      for (unsigned int i = 0; i < dX.size(); ++i)
        dX[i] = target_[o][i] - current_[o][i];
      const double fraction = pair_potential_->filters_steps()
                                  ? filter_fraction({x, nullptr, o, &dX}, o)
                                  : 1.0;
      if (fraction >= 1)
        current_[o] = target_[o];
      else
      {
        for (unsigned int i = 0; i < dX.size(); ++i)
          current_[o][i] += fraction * dX[i];
        pending_ = true;
      }
      obstacle_moved(o);
    }
  }

  void Contact::set_target_time(double time)
  {
    if (time == target_time_)
      return;
    target_time_ = time;
    for (unsigned int o = 0; o < current_.size(); ++o)
    {
      obstacle_friction_[o] = parameters_.obstacles[o].friction_at(time);
      target_[o]            = parameters_.obstacles[o].positions(time);
      if (current_[o].empty()) // first use: no sweep from nowhere
      {
        current_[o] = target_[o];
        obstacle_moved(o);
      }
    }
  }

  const Contact::Timing &Contact::timing() const
  {
    return timing_;
  }

  void Contact::prepare(const model::ShellState &state, double time)
  {
    const Stopwatch watch(timing_.detection);
    set_target_time(time);
    positions_ = shell_positions(state);
    update_stretches(state);
    if (reuse_trial_detection())
      return;
    // Lists made where the shell is now serve the obstacles' step filter
    // (an obstacle's step is small) and then the pair search.
    std::vector<Screen> obstacle_screens;
    Screen              self_screen;
    update_candidates(positions_, obstacle_screens, self_screen);
    advance_obstacles(positions_);
    find_pairs(positions_);
  }

  /// The work obstacle o's motion did on the shell since the last save():
  /// with E_o the energy of its pairs and f_o their force on the shell,
  /// dE_o = -f_o . du + (the obstacle's share), so the work its driver put
  /// in is dE_o + f_o . du, the shell's part by the trapezoidal rule on
  /// the shell's translations (the rule of the scene's other works). Exact
  /// for any rigid motion, rotations included, and for an obstacle that
  /// lags behind its prescribed position and catches up. Friction has no
  /// energy, but its dissipation D over the step is its potential within
  /// the step (lagged normal force, displacement from the step's start),
  /// so it counts as E_o does: f_o . du + D is the work of the friction
  /// force along the obstacle's own motion, 0 for a fixed obstacle.
  double Contact::step_work(unsigned int o) const
  {
    if (saved_positions_.size() != positions_.size())
      return 0;
    const Vector<double> &now    = shell_force_[o],
                         &before = saved_shell_force_[o];
    double shell_work            = 0;
    for (const unsigned int v : shell_vertices_)
    {
      const auto &dofs = model_.vertex_dofs(v);
      for (unsigned int d = 0; d < 3; ++d)
        shell_work += 0.5 * (now[dofs[d]] + before[dofs[d]]) *
                      (positions_[v][d] - saved_positions_[v][d]);
    }
    return potential_per_obstacle_[o] - saved_potential_per_obstacle_[o] +
           friction_dissipation_per_obstacle_[o] + shell_work;
  }

  void Contact::add_shell_force(const Pair &pair, const model::DofBlock &block)
  {
    for (unsigned int i = 0; i < block.dofs.size(); ++i)
      vertex_force_[block.dofs[i]] += block.vector[i];
    if (!pair.self)
      for (unsigned int i = 0; i < block.dofs.size(); ++i)
        shell_force_[pair.obstacle][block.dofs[i]] += block.vector[i];
  }

  void Contact::save()
  {
    projecting_this_step_ = false;
    trial_detection_.reset();
    for (unsigned int o = 0; o < obstacle_work_.size(); ++o)
      obstacle_work_[o] += step_work(o);
    saved_shell_force_            = shell_force_;
    saved_potential_per_obstacle_ = potential_per_obstacle_;
    saved_                        = current_;
    saved_positions_              = positions_;
    saved_time_                   = target_time_;
    lagged_normal_forces_         = normal_forces_;
    if (pair_potential_->stiffens(smallest_gap_))
      kappa_ *= 2; // the barrier is getting too stiff a spring: stiffen it
    forget_gaps();
  }

  void Contact::begin_trial()
  {
    trial_current_ = current_;
    trial_pending_ = pending_;
  }

  void Contact::end_trial()
  {
    Detection detection{positions_,
                        target_time_,
                        trial_current_,
                        current_,
                        std::vector<std::optional<Tree>>(current_.size()),
                        pending_,
                        pairs_};
    pending_ = trial_pending_;
    for (unsigned int o = 0; o < current_.size(); ++o)
      if (current_[o] != trial_current_[o])
      {
        detection.trees_after[o] = std::move(obstacle_trees_[o]);
        current_[o]              = trial_current_[o];
        obstacle_moved(o);
      }
    trial_detection_ = std::move(detection);
  }

  bool Contact::reuse_trial_detection()
  {
    std::optional<Detection> detection = std::move(trial_detection_);
    trial_detection_.reset();
    if (!detection || detection->positions != positions_ ||
        detection->target_time != target_time_ ||
        detection->obstacles_before != current_)
      return false;
    for (unsigned int o = 0; o < current_.size(); ++o)
      if (detection->obstacles_after[o] != current_[o])
      {
        current_[o]        = std::move(detection->obstacles_after[o]);
        obstacle_trees_[o] = std::move(detection->trees_after[o]);
        ++obstacle_moves_[o];
      }
    pending_ = detection->pending;
    pairs_   = std::move(detection->pairs);
    return true;
  }

  void Contact::restore()
  {
    projecting_this_step_ = parameters_.project_tangent_on_retry;
    trial_detection_.reset();
    if (saved_.empty())
      return;
    current_ = saved_;
    for (unsigned int o = 0; o < current_.size(); ++o)
      obstacle_moved(o);
  }

  bool Contact::use_projected_tangent()
  {
    if (!parameters_.project_tangent_on_stall || parameters_.project_tangent ||
        projecting_this_step_)
      return false;
    projecting_this_step_ = true;
    return true;
  }

  void Contact::check_initial_configuration(const model::ShellState &state,
                                            double                   time)
  {
    set_target_time(time);
    for (unsigned int o = 0; o < current_.size(); ++o)
    {
      current_[o] = target_[o];
      obstacle_moved(o);
    }
    saved_           = current_;
    positions_       = shell_positions(state);
    saved_positions_ = positions_;
    update_stretches(state);
    saved_time_ = time;
    find_pairs(positions_);
    for (const Pair &pair : pairs_)
    {
      const auto   p        = pair_points(pair, positions_, other_side(pair));
      const double distance = std::sqrt(pair_distance(pair, p, false).value);
      if (distance > offset(pair))
        continue;
      std::ostringstream message;
      if (pair.self)
      {
        message << "the shell starts in contact with itself (Contact/Self "
                   "contact): "
                << (pair.edge_edge ? "shell edge " : "shell vertex ")
                << pair.shell << " at " << p[0] << " is at distance "
                << distance
                << (pair.edge_edge ? " from shell edge "
                                   : " from shell triangle ")
                << pair.other << ", not more than their mean thickness "
                << offset(pair);
        throw std::runtime_error(message.str());
      }
      const Obstacle &obstacle = parameters_.obstacles[pair.obstacle];
      message << "the shell starts inside obstacle '" << obstacle.name
              << "' (Contact/Obstacle " << pair.obstacle + 1 << "): "
              << (pair.edge_edge
                      ? "the edge of shell vertices " +
                            std::to_string(shell_edges_[pair.shell][0]) +
                            " and " +
                            std::to_string(shell_edges_[pair.shell][1])
                  : pair.shell_vertex_side
                      ? "shell vertex " + std::to_string(pair.shell)
                      : "shell triangle " + std::to_string(pair.shell))
              << " at " << p[pair.shell_vertex_side ? 0 : 1]
              << " is at distance " << distance
              << " from it, not more than the offset " << offset(pair)
              << " (half the shell thickness plus the obstacle's Offset)";
      throw std::runtime_error(message.str());
    }
    forget_gaps();
  }
} // namespace coshell::contact
