// The contact contribution of a small plate over a rigid plane, assembled
// as ShellProblem does: its tangent against central differences of its
// forces, with the barrier, the penalty and friction; its forces against
// central differences of its energy (the barrier, the penalty and
// friction lagged as in IPC are potentials); the equal and opposite
// force on the obstacle and the slopes of its force and moment (what a
// linearized step reports its load with); the same tangent and energy
// checks for self contact and edge-edge pairs.

#include <coshell/base/expressions.h>
#include <coshell/base/tangent_matrix.h>
#include <coshell/contact/contact.h>
#include <coshell/mesh/mesh.h>
#include <coshell/model/shell_problem.h>

#include <deal.II/base/multithread_info.h>
#include <deal.II/grid/tria_description.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <memory>
#include <utility>
#include <vector>

namespace
{
  using namespace coshell;
  using dealii::Point;
  using dealii::Vector;

  /// Four triangles covering [-5, 5]^2 at height z, around a vertex that
  /// lies under the plate (so obstacle vertices meet shell triangles too).
  contact::Obstacle plane(double z, double friction)
  {
    contact::Obstacle obstacle;
    obstacle.name        = "plane";
    obstacle.vertices    = {Point<3>(-5, -5, z), Point<3>(5, -5, z),
                            Point<3>(5, 5, z), Point<3>(-5, 5, z),
                            Point<3>(1.1, 0.7, z)};
    obstacle.triangles   = {{0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}};
    obstacle.vertex_area = {1, 1, 1, 1, 1}; // not used by contact
    obstacle.motion.translation =
        base::parse_expressions<1>("0; 0; 0", 3, "x,t", true, "t", "test");
    obstacle.motion.angle =
        base::parse_expressions<1>("0", 1, "x,t", true, "t", "test");
    obstacle.motion.axis          = dealii::Tensor<1, 3>({0, 0, 1});
    obstacle.friction_coefficient = friction;
    return obstacle;
  }

  struct Assembled
  {
    Vector<double>             force;
    dealii::FullMatrix<double> tangent;
  };

  Assembled assemble(contact::ContactContribution &contribution,
                     const model::ShellState      &state,
                     double                        time,
                     unsigned int                  n)
  {
    Assembled out{Vector<double>(n), dealii::FullMatrix<double>(n, n)};
    const model::EvaluationPoint point{state, time, 1, 0, 0};
    contribution.prepare(point);
    contribution.add_blocks(
        point,
        [&](const model::DofBlock &block)
        {
          for (unsigned int i = 0; i < block.dofs.size(); ++i)
          {
            out.force[block.dofs[i]] += block.vector[i];
            for (unsigned int j = 0; j < block.dofs.size(); ++j)
              out.tangent(block.dofs[i], block.dofs[j]) += block.matrix(i, j);
          }
        },
        true);
    return out;
  }

  model::ElementParameters unit_thickness()
  {
    model::ElementParameters element;
    element.material.thickness = 1;
    return element;
  }

  /// Barrier, activation 0.1, kappa 1, exact (unprojected) tangent.
  contact::ContactParameters barrier_parameters()
  {
    contact::ContactParameters parameters;
    parameters.method              = contact::Method::barrier;
    parameters.activation_distance = 0.1;
    parameters.barrier_stiffness   = 1;
    parameters.project_tangent     = false;
    return parameters;
  }

  /// What 'measure' takes from the assembly at time 1 with translation
  /// DoF j moved by +h and by -h; the state is put back.
  template<typename Measure>
  auto measured_both_ways(contact::ContactContribution &contribution,
                          model::ShellState            &state,
                          unsigned int                  n,
                          unsigned int                  j,
                          double                        h,
                          const Measure                &measure)
  {
    Vector<double> step(n);
    step[j] = h;
    state.apply_increment(step);
    const auto plus = measure(assemble(contribution, state, 1, n));
    step[j]         = -2 * h;
    state.apply_increment(step);
    const auto minus = measure(assemble(contribution, state, 1, n));
    step[j]          = h;
    state.apply_increment(step);
    return std::make_pair(plus, minus);
  }

  /// The contribution's tangent at time 1 against central differences of
  /// its forces over every translation (contact does not see rotations);
  /// returns what was assembled there.
  Assembled
  expect_tangent_matches_forces(contact::ContactContribution &contribution,
                                model::ShellState            &state,
                                unsigned int                  n)
  {
    const Assembled at    = assemble(contribution, state, 1, n);
    double          scale = 0;
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = 0; j < n; ++j)
        scale = std::max(scale, std::abs(at.tangent(i, j)));
    EXPECT_GT(scale, 0);
    const double h = 1e-7;
    for (unsigned int j = 0; j < n; ++j)
    {
      if (j % 6 >= 3)
        continue;
      const auto [plus, minus] =
          measured_both_ways(contribution, state, n, j, h,
                             [](const Assembled &at) { return at.force; });
      for (unsigned int i = 0; i < n; ++i)
        EXPECT_NEAR(-(plus[i] - minus[i]) / (2 * h), at.tangent(i, j),
                    1e-5 * scale)
            << "entry " << i << ", " << j;
    }
    return at;
  }

  /// The plate [0, 2]^2 in z = 0 (2 x 2 squares of 4 triangles), h = 1.
  struct UnitPlate
  {
    mesh::Surface surface;
    // Members are built in order: the mesh before the model on it.
    const bool meshed =
        (mesh::make_rectangle(
             surface, 2, 2, 2, 2, mesh::TrianglePattern::crossed),
         true);
    const model::ShellModel model{surface, unit_thickness(),
                                  dealii::Tensor<1, 3>({0, 0, 1})};
    model::ShellState       state{model, false};
  };

  /// Action and reaction at time 1: the force on the plate's one
  /// obstacle balances the shell's, friction included. Assembles anew
  /// (finite differences leave the last assembly at a perturbed state).
  const contact::ObstacleLoad &
  expect_action_and_reaction(const contact::Contact       &contact,
                             contact::ContactContribution &contribution,
                             UnitPlate                    &plate,
                             unsigned int                  n)
  {
    const Assembled      at = assemble(contribution, plate.state, 1, n);
    dealii::Tensor<1, 3> on_shell;
    for (unsigned int v = 0; v < plate.surface.n_vertices(); ++v)
      for (unsigned int c = 0; c < 3; ++c)
        on_shell[c] += at.force[plate.model.vertex_dofs(v)[c]];
    const auto &load = contact.obstacle_loads()[0];
    for (unsigned int c = 0; c < 3; ++c)
      EXPECT_NEAR(load.force[c], -on_shell[c], 1e-12 * on_shell.norm());
    return load;
  }

  /// The force (moment: the moment about the origin) and its slopes.
  dealii::Tensor<1, 3> load_part(const contact::ObstacleLoad &load, bool moment)
  {
    return moment ? load.moment : load.force;
  }

  /// The obstacle's load slopes (force and moment) at time 1 against
  /// central differences of its load over every translation of the shell,
  /// and the load carried along a small move by extrapolate_loads()
  /// against the load assembled there (second-order close).
  void
  expect_force_slopes_match_loads(contact::Contact             &contact,
                                  contact::ContactContribution &contribution,
                                  model::ShellState            &state,
                                  unsigned int                  n)
  {
    const auto  &loads = contact.obstacle_loads();
    const double h     = 1e-7;
    for (const bool moment : {false, true})
    {
      assemble(contribution, state, 1, n);
      std::array<Vector<double>, 3> gradients;
      double                        scale = 0;
      for (unsigned int k = 0; k < 3; ++k)
      {
        gradients[k] = contact.load_gradient(0, k, moment);
        scale        = std::max(scale, gradients[k].linfty_norm());
      }
      EXPECT_GT(scale, 0);
      for (unsigned int j = 0; j < n; ++j)
      {
        if (j % 6 >= 3)
          continue;
        const auto [plus, minus] = measured_both_ways(
            contribution, state, n, j, h,
            [&](const Assembled &) { return load_part(loads[0], moment); });
        for (unsigned int k = 0; k < 3; ++k)
          EXPECT_NEAR((plus[k] - minus[k]) / (2 * h), gradients[k][j],
                      1e-5 * scale)
              << (moment ? "moment" : "force") << " axis " << k << ", DoF "
              << j;
      }
    }
    // The extrapolation's error is second order: far below its change.
    Vector<double> move(n);
    for (unsigned int j = 0; j < n; ++j)
      if (j % 6 < 3)
        move[j] = 1e-4 * (1 + j % 5) * (j % 2 ? 1 : -1);
    assemble(contribution, state, 1, n);
    const contact::ObstacleLoad start = loads[0];
    contact.extrapolate_loads(move);
    const contact::ObstacleLoad extrapolated = loads[0];
    state.apply_increment(move);
    assemble(contribution, state, 1, n);
    for (const bool moment : {false, true})
    {
      const auto change =
          load_part(extrapolated, moment) - load_part(start, moment);
      EXPECT_GT(change.norm(), 0);
      EXPECT_LT((load_part(extrapolated, moment) - load_part(loads[0], moment))
                    .norm(),
                0.05 * change.norm())
          << (moment ? "moment" : "force");
    }
    move *= -1;
    state.apply_increment(move);
  }

  /// Contact is a potential: the contribution's forces at time 1 against
  /// central differences of its energy (the pairs' barrier or penalty
  /// energy, and friction's lagged potential, Contact::potential() plus
  /// the step's friction dissipation) over every translation (force on
  /// the shell = -gradient).
  void expect_forces_are_minus_potential_gradient(
      contact::ContactContribution &contribution,
      model::ShellState            &state,
      unsigned int                  n)
  {
    ASSERT_TRUE(contribution.has_potential());
    const model::EvaluationPoint point{state};
    const Assembled              at    = assemble(contribution, state, 1, n);
    const double                 scale = at.force.linfty_norm();
    EXPECT_GT(scale, 0);
    const double h = 1e-7;
    for (unsigned int j = 0; j < n; ++j)
    {
      if (j % 6 >= 3)
        continue;
      const auto [plus, minus] = measured_both_ways(
          contribution, state, n, j, h,
          [&](const Assembled &) { return contribution.global_energy(point); });
      EXPECT_NEAR(-(plus - minus) / (2 * h), at.force[j], 1e-5 * scale)
          << "DoF " << j;
    }
  }

  /// Plate [0, 2]^2, h = 1 (offset 0.5), over the plane z = -0.55 (gap
  /// 0.05 < activation 0.1); after a converged state at t = 0 the plate is
  /// moved sideways and down, and the tangent at t = 1 is checked. With
  /// 'penalty' the law is the smoothed penalty (stiffness 10, smoothing
  /// 0.005), and the plate sinks 0.06 further, into the plane.
  void check_tangent(double friction, bool penalty = false)
  {
    UnitPlate                  plate;
    const auto                &surface    = plate.surface;
    const auto                &model      = plate.model;
    auto                      &state      = plate.state;
    contact::ContactParameters parameters = barrier_parameters();
    if (penalty)
    {
      parameters.method            = contact::Method::penalty;
      parameters.penalty_stiffness = 10;
      parameters.penalty_smoothing = 0.005;
    }
    parameters.stiction_velocity = 0.01;
    parameters.obstacles         = {plane(-0.55, friction)};
    contact::Contact contact(model, parameters);
    contact.follow_force_slopes();
    contact.check_initial_configuration(state, 0);
    contact::ContactContribution contribution(contact);
    const unsigned int           n = model.n_dofs();
    assemble(contribution, state, 0, n);
    contribution.save();
    // A sliding and sinking motion, different at each vertex.
    Vector<double> move(n);
    for (unsigned int v = 0; v < surface.n_vertices(); ++v)
    {
      const auto &dofs = model.vertex_dofs(v);
      move[dofs[0]]    = 0.004 + 0.001 * v;
      move[dofs[1]]    = -0.002 * (v % 3);
      move[dofs[2]]    = -0.01 - 0.002 * (v % 2) - (penalty ? 0.06 : 0);
    }
    state.apply_increment(move);
    expect_tangent_matches_forces(contribution, state, n);
    expect_forces_are_minus_potential_gradient(contribution, state, n);
    expect_force_slopes_match_loads(contact, contribution, state, n);
    const auto &load =
        expect_action_and_reaction(contact, contribution, plate, n);
    EXPECT_GT(load.active_pairs, 0u);
  }
} // namespace

TEST(ContactAssembly, BarrierTangentMatchesFiniteDifferences)
{
  check_tangent(0);
}

TEST(ContactAssembly, FrictionTangentMatchesFiniteDifferences)
{
  check_tangent(0.5);
}

TEST(ContactAssembly, PenaltyTangentMatchesFiniteDifferences)
{
  check_tangent(0, true);
}

namespace
{
  /// Two plates as one shell mesh: [0, 2]^2 in z = 0 (2 x 2 squares) and,
  /// non-matching, [0, 2]^2 shifted by 'shift' (3 x 3 squares).
  void make_two_plates(mesh::Surface              &surface,
                       const dealii::Tensor<1, 3> &shift)
  {
    std::vector<Point<3>>            vertices;
    std::vector<dealii::CellData<2>> cells;
    for (const unsigned int n : {2u, 3u})
    {
      mesh::Surface piece;
      mesh::make_rectangle(piece, 2, 2, n, n, mesh::TrianglePattern::crossed);
      const unsigned int first = vertices.size();
      for (const auto &v : piece.get_vertices())
        vertices.push_back(n == 2 ? v : v + shift);
      for (const auto &cell : piece.active_cell_iterators())
      {
        dealii::CellData<2> data(3);
        for (unsigned int i = 0; i < 3; ++i)
          data.vertices[i] = first + cell->vertex_index(i);
        cells.push_back(data);
      }
    }
    surface.create_triangulation(vertices, cells, dealii::SubCellData());
  }
} // namespace

// Self contact: the upper plate (h = 1) 1.05 above the lower (gap 0.05 <
// activation 0.1), then moved down and sideways: the tangent of the
// vertex-triangle pairs of the shell with itself against central
// differences, and the forces, internal to the shell, summing to zero.
namespace
{
  /// The force on the upper plate of make_two_plates.
  dealii::Tensor<1, 3> upper_plate_force(const mesh::Surface     &surface,
                                         const model::ShellModel &model,
                                         const Vector<double>    &force)
  {
    dealii::Tensor<1, 3> total;
    for (unsigned int v = 0; v < surface.n_vertices(); ++v)
      if (surface.get_vertices()[v][2] > 0.5)
        for (unsigned int c = 0; c < 3; ++c)
          total[c] += force[model.vertex_dofs(v)[c]];
    return total;
  }
  dealii::Tensor<1, 3> last_upper_force;

  /// Returns the number of active self-contact pairs.
  unsigned int check_self_contact(bool edge_edge, double friction = 0)
  {
    mesh::Surface surface;
    make_two_plates(surface, dealii::Tensor<1, 3>({-0.3, 0.2, 1.05}));
    const model::ShellModel    model(surface, unit_thickness(),
                                     dealii::Tensor<1, 3>({0, 0, 1}));
    model::ShellState          state(model, false);
    contact::ContactParameters parameters = barrier_parameters();
    parameters.self_contact               = true;
    parameters.edge_edge_pairs            = edge_edge;
    parameters.self_friction_coefficient  = friction;
    parameters.stiction_velocity          = 0.01;
    contact::Contact contact(model, parameters);
    contact.check_initial_configuration(state, 0);
    contact::ContactContribution contribution(contact);
    const unsigned int           n = model.n_dofs();
    // A converged state at t = 0, whose pairs friction acts on (lagged).
    assemble(contribution, state, 0, n);
    contribution.save();
    Vector<double> move(n);
    for (unsigned int v = 0; v < surface.n_vertices(); ++v)
      if (surface.get_vertices()[v][2] > 0.5)
      {
        const auto &dofs = model.vertex_dofs(v);
        move[dofs[0]]    = 0.004 + 0.001 * v;
        move[dofs[2]]    = -0.01 - 0.002 * (v % 2);
      }
    state.apply_increment(move);
    const Assembled at = expect_tangent_matches_forces(contribution, state, n);
    expect_forces_are_minus_potential_gradient(contribution, state, n);
    EXPECT_GT(contact.self_active_pairs(), 0u);
    dealii::Tensor<1, 3> total;
    double               largest = 0;
    for (unsigned int v = 0; v < surface.n_vertices(); ++v)
      for (unsigned int c = 0; c < 3; ++c)
      {
        total[c] += at.force[model.vertex_dofs(v)[c]];
        largest =
            std::max(largest, std::abs(at.force[model.vertex_dofs(v)[c]]));
      }
    EXPECT_GT(largest, 0);
    EXPECT_LT(total.norm(), 1e-12 * largest);
    last_upper_force = upper_plate_force(surface, model, at.force);
    return contact.self_active_pairs();
  }
} // namespace

TEST(ContactAssembly, SelfContactTangentMatchesFiniteDifferencesAndBalances)
{
  check_self_contact(false);
}

// The same with shell edges against shell edges (the upper plate's 3 x 3
// squares against the lower's 2 x 2: their edges cross between vertices).
TEST(ContactAssembly, SelfEdgeEdgeTangentMatchesFiniteDifferencesAndBalances)
{
  EXPECT_GT(check_self_contact(true), check_self_contact(false));
}

// Friction of the shell against itself, vertex-triangle and edge-edge
// pairs: the tangent, and the forces summing to zero as above; the upper
// plate, moved by +x, is held back (-x) beyond the frictionless pairs'
// lateral force, by at most mu times the lagged normal force (which is
// not the present one: the plate has sunk since).
TEST(ContactAssembly, SelfContactFrictionTangentMatchesFiniteDifferences)
{
  for (const bool edge_edge : {false, true})
  {
    SCOPED_TRACE(edge_edge ? "with edge-edge pairs" : "vertex-triangle");
    check_self_contact(edge_edge, 0);
    const dealii::Tensor<1, 3> frictionless = last_upper_force;
    check_self_contact(edge_edge, 0.5);
    const double friction_x = last_upper_force[0] - frictionless[0];
    EXPECT_LT(friction_x, 0);
    EXPECT_LE(-friction_x, 0.5 * frictionless[2]);
  }
}

namespace
{
  /// A rigid knife over the plate [0, 2]^2: a straight edge from
  /// (x0, -3, z) to (x0 + 8 tilt, 5, z), faces rising 1 in 3 to either
  /// side (shallow, so that they stay out of the plate vertices' reach);
  /// its vertices are all beyond the plate.
  contact::Obstacle knife(double x0, double tilt, double z)
  {
    contact::Obstacle obstacle = plane(0, 0);
    obstacle.name              = "knife";
    const double x1            = x0 + 8 * tilt;
    obstacle.vertices          = {
                 Point<3>(x0, -3, z),         Point<3>(x1, 5, z),
                 Point<3>(x0 - 3, -3, z + 1), Point<3>(x1 - 3, 5, z + 1),
                 Point<3>(x0 + 3, -3, z + 1), Point<3>(x1 + 3, 5, z + 1)};
    obstacle.triangles   = {{0, 1, 3}, {0, 3, 2}, {0, 4, 5}, {0, 5, 1}};
    obstacle.vertex_area = std::vector<double>(6, 1);
    return obstacle;
  }

  dealii::Tensor<1, 3> last_knife_force;

  /// Plate [0, 2]^2 (h = 1, offset 0.5) under a knife 0.55 above it, with
  /// edge-edge pairs; the plate is then moved up (by 0.020 to 0.024) so
  /// that they are inside the barrier (distance 0.556-0.56 < 0.6) while
  /// every plate vertex stays out of reach of the knife's edge
  /// (sqrt(0.25^2 + 0.556^2) > 0.6 for the knife at x = 0.75), and the
  /// tangent is checked. Returns the number of active pairs on the knife.
  unsigned int check_knife_tangent(double x0,
                                   double tilt,
                                   bool   edge_edge,
                                   double friction = 0)
  {
    UnitPlate                  plate;
    const auto                &surface           = plate.surface;
    const auto                &model             = plate.model;
    auto                      &state             = plate.state;
    contact::ContactParameters parameters        = barrier_parameters();
    parameters.edge_edge_pairs                   = edge_edge;
    parameters.obstacles                         = {knife(x0, tilt, 0.58)};
    parameters.obstacles[0].friction_coefficient = friction;
    parameters.stiction_velocity                 = 0.01;
    contact::Contact contact(model, parameters);
    contact.check_initial_configuration(state, 0);
    contact::ContactContribution contribution(contact);
    const unsigned int           n = model.n_dofs();
    // A converged state at t = 0, whose pairs friction acts on (lagged).
    assemble(contribution, state, 0, n);
    contribution.save();
    // Up, and with friction also along the knife's edge (+y), which
    // leaves every distance to the edge as it is.
    Vector<double> move(n);
    for (unsigned int v = 0; v < surface.n_vertices(); ++v)
    {
      const auto &dofs = model.vertex_dofs(v);
      move[dofs[1]]    = friction > 0 ? 0.005 + 0.002 * (v % 2) : 0;
      move[dofs[2]]    = 0.02 + 0.002 * (v % 3);
    }
    state.apply_increment(move);
    if (!edge_edge)
    {
      assemble(contribution, state, 1, n);
      return contact.obstacle_loads()[0].active_pairs;
    }
    expect_tangent_matches_forces(contribution, state, n);
    expect_forces_are_minus_potential_gradient(contribution, state, n);
    const auto &load =
        expect_action_and_reaction(contact, contribution, plate, n);
    last_knife_force = load.force;
    return load.active_pairs;
  }
} // namespace

// Edge-edge pairs: a knife whose edge crosses the plate's edges between
// their vertices (x = 0.75, no vertex of either side near the other's
// faces) is seen by edge-edge pairs only; their tangent against central
// differences. Then the knife nearly parallel to the plate's edge x = 1
// (tilt 0.01: sin^2 = 1e-4 < 1e-3, so the mollifier acts): the tangent
// of the mollified pairs, product rule included (the knife's edge runs
// 0.005-0.025 beside that edge, over no vertex).
TEST(ContactAssembly, EdgeEdgePairsHoldAKnifeBetweenVertices)
{
  EXPECT_EQ(check_knife_tangent(0.75, 0, false), 0u);
  EXPECT_GT(check_knife_tangent(0.75, 0, true), 0u);
}

// Friction on edge-edge pairs: the plate slid along the knife's edge
// drags the knife along (+y) by at most mu times the normal force.
TEST(ContactAssembly, EdgeEdgeFrictionTangentMatchesFiniteDifferences)
{
  EXPECT_GT(check_knife_tangent(0.75, 0, true, 0.5), 0u);
  EXPECT_GT(last_knife_force[1], 0);
  EXPECT_LE(last_knife_force[1], 0.5 * last_knife_force[2]);
}

TEST(ContactAssembly, EdgeEdgeMollifierTangentMatchesFiniteDifferences)
{
  EXPECT_GT(check_knife_tangent(0.975, 0.01, true), 0u);
}

// The interactive input path: 0 before any sample, a ramp from the
// present to each sample, held after the last; a sample appended later
// leaves the times up to the present where they were.
TEST(ContactAssembly, InputPathRampsFromThePresentAndKeepsThePast)
{
  contact::InputPath path;
  EXPECT_EQ(path.value(0.5), 0.0);
  path.append(0.0, 1.0, 2.0);
  EXPECT_DOUBLE_EQ(path.value(0.25), 0.5);
  EXPECT_EQ(path.value(1.0), 2.0);
  EXPECT_EQ(path.value(3.0), 2.0); // held
  const double held = path.value(1.5);
  path.append(2.0, 3.0, 4.0); // the run reached t = 2 with the input held
  EXPECT_EQ(path.value(1.5), held);
  EXPECT_EQ(path.value(2.0), 2.0);
  EXPECT_DOUBLE_EQ(path.value(2.5), 3.0);
  EXPECT_THROW(path.append(3.0, 3.0, 5.0), std::invalid_argument);

  // An obstacle moves by the input along its direction, on top of its
  // Translation.
  contact::Obstacle obstacle = plane(0.1, 0);
  obstacle.input_direction   = dealii::Tensor<1, 3>({0, 0, -0.5});
  obstacle.input             = std::make_shared<contact::InputPath>(path);
  const auto moved           = obstacle.positions(2.5);
  EXPECT_DOUBLE_EQ(moved[4][2], 0.1 - 0.5 * 3.0);
  EXPECT_DOUBLE_EQ(moved[4][0], 1.1);
}

// With several threads ShellProblem makes the contact blocks on the task
// that searches the pairs, beside the cells' assembly, keeps them and
// adds them after the cells; with one it adds them as they are made.
// Contact alone (the cells add nothing), with friction: the residual and
// the tangent of both ways are the same to the bit.
TEST(ContactAssembly, BlocksMadeBesideTheCellsAreThoseMadeInlineToTheBit)
{
  UnitPlate                  plate;
  contact::ContactParameters parameters = barrier_parameters();
  parameters.stiction_velocity          = 0.01;
  parameters.obstacles                  = {plane(-0.55, 0.5)};
  contact::Contact contact(plate.model, parameters);
  contact.check_initial_configuration(plate.state, 0);
  std::vector<std::unique_ptr<model::Contribution>> contributions;
  contributions.push_back(
      std::make_unique<contact::ContactContribution>(contact));
  dealii::AffineConstraints<double> constraints;
  constraints.close();
  model::ShellProblem problem(plate.model, plate.state, constraints,
                              std::move(contributions));
  const unsigned int  n = plate.model.n_dofs();
  Vector<double>      sink(n);
  for (unsigned int v = 0; v < plate.surface.n_vertices(); ++v)
    sink[plate.model.vertex_dofs(v)[2]] = -0.01 - 0.002 * (v % 2);
  problem.apply_increment(sink);

  const unsigned int threads  = dealii::MultithreadInfo::n_threads();
  const auto         evaluate = [&](unsigned int limit)
  {
    dealii::MultithreadInfo::set_thread_limit(limit);
    EXPECT_EQ(dealii::MultithreadInfo::n_threads(), limit);
    std::pair<Vector<double>, base::TangentMatrix> result;
    result.first.reinit(n);
    problem.reinit_tangent(result.second);
    problem.evaluate(result.first, &result.second);
    return result;
  };
  auto inline_made = evaluate(1);
  auto beside      = evaluate(2);
  dealii::MultithreadInfo::set_thread_limit(threads);
  ASSERT_GT(inline_made.first.l2_norm(), 0);
  for (unsigned int k = 0; k < n; ++k)
    ASSERT_EQ(beside.first[k], inline_made.first[k]) << "residual " << k;
  const auto &matrix = inline_made.second.serial();
  for (unsigned int i = 0; i < n; ++i)
    for (auto e = matrix.begin(i); e != matrix.end(i); ++e)
      ASSERT_EQ(beside.second.serial().el(i, e->column()), e->value())
          << "entry (" << i << ", " << e->column() << ")";
}

namespace
{
  /// The force and tangent of a contact that has searched at every one of
  /// the positions before against those of a contact made at this one,
  /// compared to the bit.
  void expect_same_assembly(const Assembled &searched,
                            const Assembled &fresh,
                            unsigned int     step)
  {
    const unsigned int n = searched.force.size();
    for (unsigned int i = 0; i < n; ++i)
    {
      ASSERT_EQ(searched.force[i], fresh.force[i])
          << "force " << i << " at step " << step;
      for (unsigned int j = 0; j < n; ++j)
        ASSERT_EQ(searched.tangent(i, j), fresh.tangent(i, j))
            << "tangent (" << i << ", " << j << ") at step " << step;
    }
  }
} // namespace

// The pair search skips a listed pair whose distance, found at an
// earlier search, is still beyond its reach after the largest moves
// since (the search clock). A plate slid across a knife that rises
// (shell vertices and edges against it) and away from a plane that sinks
// with a vertex under the plate (that vertex against the plate's
// triangles, its pairs leaving the barrier's reach): at every step the contact
// that searched at all the steps before assembles what a contact made at that
// step assembles, to the bit.
TEST(ContactAssembly, PairsSkippedByTheSearchClockAreThoseOutOfReach)
{
  UnitPlate                  plate;
  contact::ContactParameters parameters = barrier_parameters();
  parameters.obstacles = {knife(0.3, 0.01, 0.57), plane(-0.58, 0)};
  parameters.obstacles[1].motion.translation = base::parse_expressions<1>(
      "0; 0; -0.002 * t", 3, "x,t", true, "t", "test");
  parameters.obstacles[0].motion.translation = base::parse_expressions<1>(
      "0; 0; 0.001 * t", 3, "x,t", true, "t", "test");
  contact::Contact searched(plate.model, parameters);
  searched.check_initial_configuration(plate.state, 0);
  contact::ContactContribution contribution(searched);
  const unsigned int           n = plate.model.n_dofs();
  Vector<double>               move(n);
  unsigned int                 steps_in_contact = 0, steps_on_plane = 0;
  for (unsigned int step = 1; step <= 40; ++step)
  {
    for (unsigned int v = 0; v < plate.surface.n_vertices(); ++v)
    {
      const auto &dofs = plate.model.vertex_dofs(v);
      const auto &x    = plate.surface.get_vertices()[v];
      move[dofs[0]]    = 0.03;
      move[dofs[2]]    = 0.0005 * (1 + x[0]) + 0.0002 * (v % 3);
    }
    plate.state.apply_increment(move);
    const Assembled  at_step = assemble(contribution, plate.state, step, n);
    contact::Contact fresh(plate.model, parameters);
    fresh.check_initial_configuration(plate.state, step);
    contact::ContactContribution fresh_contribution(fresh);
    expect_same_assembly(
        at_step, assemble(fresh_contribution, plate.state, step, n), step);
    if (searched.obstacle_loads()[0].active_pairs > 0)
      ++steps_in_contact;
    if (searched.obstacle_loads()[1].active_pairs > 0)
      ++steps_on_plane;
  }
  EXPECT_GE(steps_in_contact, 10u);
  EXPECT_LE(steps_in_contact, 35u);
  EXPECT_GE(steps_on_plane, 1u);
  EXPECT_LT(steps_on_plane, 40u);
}

// A shell whose thickness changes (Element/Thickness stretch): the offsets
// follow h0 lambda / 2, so the pairs' energy depends on the stretches. Its
// force on every translation and stretch against central differences of
// the energy, and the tangent's columns against central differences of
// the force; vertex-triangle and edge-edge pairs with a plane, then self
// contact of two plates.
namespace
{
  model::ElementParameters stretching_unit_thickness()
  {
    model::ElementParameters element  = unit_thickness();
    element.formulation               = model::Formulation::corotational;
    element.thickness_stretch         = true;
    element.options.membrane_in_plane = false;
    return element;
  }

  /// Every translation and stretch DoF of 'model' (contact sees no
  /// rotation).
  std::vector<unsigned int> contact_dofs(const model::ShellModel &model)
  {
    std::vector<unsigned int> dofs;
    for (unsigned int j = 0; j < model.n_dofs(); ++j)
      if (j >= model.n_fe_dofs() || j % 6 < 3)
        dofs.push_back(j);
    return dofs;
  }

  void expect_stretch_terms_match_differences(
      contact::ContactContribution &contribution,
      const model::ShellModel      &model,
      model::ShellState            &state)
  {
    const unsigned int           n = model.n_dofs();
    const model::EvaluationPoint point{state};
    const Assembled              at = assemble(contribution, state, 1, n);
    double force_scale = at.force.linfty_norm(), scale = 0;
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = 0; j < n; ++j)
        scale = std::max(scale, std::abs(at.tangent(i, j)));
    ASSERT_GT(force_scale, 0);
    bool stretch_force = false;
    for (auto j = model.n_fe_dofs(); j < n; ++j)
      stretch_force = stretch_force || at.force[j] != 0;
    EXPECT_TRUE(stretch_force);
    const double h = 1e-7;
    for (const unsigned int j : contact_dofs(model))
    {
      const auto [energy_plus, energy_minus] = measured_both_ways(
          contribution, state, n, j, h,
          [&](const Assembled &) { return contribution.global_energy(point); });
      EXPECT_NEAR(-(energy_plus - energy_minus) / (2 * h), at.force[j],
                  1e-5 * force_scale)
          << "DoF " << j;
      const auto [plus, minus] =
          measured_both_ways(contribution, state, n, j, h,
                             [](const Assembled &at) { return at.force; });
      for (const unsigned int i : contact_dofs(model))
        EXPECT_NEAR(-(plus[i] - minus[i]) / (2 * h), at.tangent(i, j),
                    1e-5 * scale)
            << "entry " << i << ", " << j;
    }
  }

  /// Stretches of 0.98 to 1.01 at every vertex, different around each
  /// vertex (triangles sharing a closest feature would otherwise tie, and
  /// the pair kept of a tie changes with the sign of a difference), and a
  /// sinking, sliding motion (of the upper plate only, if 'upper_only').
  Vector<double> squeeze_and_slide(const mesh::Surface     &surface,
                                   const model::ShellModel &model,
                                   bool                     upper_only)
  {
    Vector<double> move(model.n_dofs());
    for (unsigned int v = 0; v < surface.n_vertices(); ++v)
    {
      move[model.thickness_dof(v)] = 0.01 - 0.003 * (v % 7) - 0.0001 * v;
      if (upper_only && surface.get_vertices()[v][2] < 0.5)
        continue;
      const auto &dofs = model.vertex_dofs(v);
      move[dofs[0]]    = 0.004 + 0.001 * v;
      move[dofs[2]]    = -0.01 - 0.002 * (v % 2);
    }
    return move;
  }
} // namespace

namespace
{
  /// 'surface' (unit thickness, stretching) in contact under
  /// 'parameters', checked at t = 0.
  struct StretchingContact
  {
    StretchingContact(const mesh::Surface              &surface,
                      const contact::ContactParameters &parameters)
        : model(surface,
                stretching_unit_thickness(),
                dealii::Tensor<1, 3>({0, 0, 1})),
          state(model, true), contact(model, parameters), contribution(contact)
    {
      contact.check_initial_configuration(state, 0);
    }
    const model::ShellModel      model;
    model::ShellState            state;
    contact::Contact             contact;
    contact::ContactContribution contribution;
  };

  /// The stretch terms of 'surface' under 'parameters', after a converged
  /// state at t = 0 and squeeze_and_slide.
  void check_stretch_terms(const mesh::Surface              &surface,
                           const contact::ContactParameters &parameters,
                           bool                              upper_only)
  {
    StretchingContact scene(surface, parameters);
    assemble(scene.contribution, scene.state, 0, scene.model.n_dofs());
    scene.contribution.save();
    scene.state.apply_increment(
        squeeze_and_slide(surface, scene.model, upper_only));
    expect_stretch_terms_match_differences(scene.contribution, scene.model,
                                           scene.state);
  }
} // namespace

TEST(ContactAssembly, StretchTermsMatchFiniteDifferences)
{
  mesh::Surface surface;
  mesh::make_rectangle(surface, 2, 2, 2, 2, mesh::TrianglePattern::crossed);
  contact::ContactParameters parameters = barrier_parameters();
  parameters.obstacles                  = {plane(-0.55, 0)};
  check_stretch_terms(surface, parameters, false);
}

TEST(ContactAssembly, SelfContactStretchTermsMatchFiniteDifferences)
{
  mesh::Surface surface;
  make_two_plates(surface, dealii::Tensor<1, 3>({-0.3, 0.2, 1.05}));
  contact::ContactParameters parameters = barrier_parameters();
  parameters.self_contact               = true;
  check_stretch_terms(surface, parameters, true);
}

// A thickening alone, with no move, brings a pair within reach: the plane
// lies 0.9 below the plate's mid-surface, beyond the unit thickness's
// reach and the candidate lists' margin (0.5 + 0.1 + 0.25) when the lists
// are made; stretched to 1.7 the plate's half thickness is 0.85, and the
// pairs, their forces and the tangent must be those of a contact that
// makes its lists at the stretched state.
TEST(ContactAssembly, ThickeningBringsUnlistedPairsWithinReach)
{
  mesh::Surface surface;
  mesh::make_rectangle(surface, 2, 2, 2, 2, mesh::TrianglePattern::crossed);
  contact::ContactParameters parameters = barrier_parameters();
  parameters.obstacles                  = {plane(-0.9, 0)};
  StretchingContact  scene(surface, parameters);
  const unsigned int n = scene.model.n_dofs();
  EXPECT_EQ(assemble(scene.contribution, scene.state, 0, n).force.linfty_norm(),
            0);
  scene.contribution.save();
  Vector<double> thickening(n);
  for (unsigned int v = 0; v < surface.n_vertices(); ++v)
    thickening[scene.model.thickness_dof(v)] = 0.7;
  scene.state.apply_increment(thickening);
  const Assembled thickened = assemble(scene.contribution, scene.state, 1, n);
  EXPECT_GT(thickened.force.linfty_norm(), 0);
  contact::Contact fresh(scene.model, parameters);
  fresh.check_initial_configuration(scene.state, 1);
  contact::ContactContribution fresh_contribution(fresh);
  expect_same_assembly(thickened,
                       assemble(fresh_contribution, scene.state, 1, n), 1);
}
