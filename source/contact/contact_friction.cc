// Smoothed Coulomb friction of the contact pairs (IPC, Li et al. 2020,
// section 5): the tangential relative displacement u of the pair's closest
// points over the step, against the obstacle's, meets the force
// F = -mu lambda f1(|u|) u / |u|, with f1(x) = 2x/eps - x^2/eps^2 below
// eps = max((stiction velocity) * (step duration), stiction displacement)
// and 1 above. The pairs, their
// normal force lambda, normal n and closest point's weights are those of
// the last converged state (lagged), fixed through the step. The same for
// shell against obstacle and against itself, vertex-triangle and edge-edge
// pairs: only the weights of the closest points differ.

#include <coshell/contact/contact.h>

#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>

namespace coshell::contact
{
  using namespace dealii;

  namespace
  {
    /// f0(x) = int_0^x f1: the dissipation per unit mu lambda of a slip x.
    double friction_work(double x, double eps)
    {
      return x < eps ? x * x / eps - x * x * x / (3 * eps * eps) : x - eps / 3;
    }

    /// f1(x)/x and its derivative in x.
    std::pair<double, double> friction_ratio(double x, double eps)
    {
      if (x < eps)
        return {2 / eps - x / (eps * eps), -1 / (eps * eps)};
      return {1 / x, -1 / (x * x)};
    }

    /// K_ik = mu lambda w_i w_k M, M = (f1/x) P + (f1/x)' u u^T / x with
    /// P the tangential projector: positive semi-definite for every x.
    /// The shell's points are weights w[first .. first + n).
    void add_friction_tangent(const std::array<double, 4>     &w,
                              unsigned int                     first,
                              unsigned int                     n,
                              double                           mu_lambda,
                              const std::pair<double, double> &ratio_slope,
                              const Tensor<1, 3>              &u,
                              const Tensor<1, 3>              &normal,
                              FullMatrix<double>              &matrix)
    {
      const auto [ratio, slope] = ratio_slope;
      const double x            = u.norm();
      Tensor<2, 3> m;
      for (unsigned int a = 0; a < 3; ++a)
        for (unsigned int b = 0; b < 3; ++b)
          m[a][b] = ratio * ((a == b) - normal[a] * normal[b]) +
                    (x > 0 ? slope * u[a] * u[b] / x : 0.0);
      for (unsigned int i = 0; i < n; ++i)
        for (unsigned int k = 0; k < n; ++k)
          for (unsigned int a = 0; a < 3; ++a)
            for (unsigned int b = 0; b < 3; ++b)
              matrix(3 * i + a, 3 * k + b) +=
                  mu_lambda * w[first + i] * w[first + k] * m[a][b];
    }
  } // namespace

  std::array<double, 4>
  closest_point_weights(bool edge_edge, const std::array<double, 2> &parameters)
  {
    const double a = parameters[0], b = parameters[1];
    if (edge_edge)
      return {1 - a, a, -(1 - b), -b};
    return {1, -(1 - a - b), -a, -b};
  }

  Tensor<1, 3> closest_point_difference(bool edge_edge,
                                        const std::array<Point<3>, 4> &points,
                                        const std::array<double, 2> &parameters)
  {
    const std::array<double, 4> w =
        closest_point_weights(edge_edge, parameters);
    Tensor<1, 3> difference;
    for (unsigned int k = 0; k < 4; ++k)
      difference += w[k] * points[k];
    return difference;
  }

  double Contact::friction_coefficient(const Pair &pair) const
  {
    return pair.self ? parameters_.self_friction_coefficient
                     : obstacle_friction_[pair.obstacle];
  }

  double Contact::smoothing_length() const
  {
    return std::max(parameters_.stiction_velocity *
                        std::max(target_time_ - saved_time_, 0.0),
                    parameters_.stiction_displacement);
  }

  std::string Contact::friction_report() const
  {
    unsigned int n = 0;
    for (const NormalForce &lagged : lagged_normal_forces_)
      n += friction_coefficient(lagged.pair) > 0 && lagged.force > 0;
    if (n == 0)
      return "";
    // Sticking is a spring of stiffness mu lambda 2 / eps per pair: an
    // eps far below the step's motion makes it a stiff one, which Newton
    // may not get through (the plate on the plane with friction, v_s dt =
    // 1e-6 mm, fails at its first step and runs with a 1e-3 mm floor).
    std::ostringstream out;
    out << std::setprecision(3) << "; friction on " << n
        << " pairs smooths sticking over " << smoothing_length()
        << " (length units: Contact/Stiction velocity times the step, at "
           "least Contact/Stiction displacement), a stiff spring if short";
    return out.str();
  }

  /// Friction acts on the pairs that were in contact at the last
  /// converged state, with their normal force, normal and closest point
  /// of then (IPC's lagging): within a step it is the gradient of a fixed
  /// potential, so Newton converges as on an elastic problem, and a pair
  /// that leaves the barrier's reach during the iterations does not switch
  /// its friction off and on.
  void Contact::add_friction_terms(const model::BlockSink &sink,
                                   bool                    with_tangent)
  {
    PairBlocks blocks;
    for (const NormalForce &lagged : lagged_normal_forces_)
    {
      if (friction_coefficient(lagged.pair) == 0)
        continue;
      model::DofBlock &block = pair_dofs(lagged.pair, blocks);
      block.vector           = 0;
      if (with_tangent)
        block.matrix = 0;
      const Tensor<1, 3> application =
          add_friction(lagged, with_tangent, block);
      // Friction's block is exact (positive semi-definite as it stands).
      if (with_tangent && follows_force(lagged.pair))
        add_force_slopes(lagged.pair, block.dofs, block.matrix, application);
      add_shell_force(lagged.pair, block);
      sink(block);
    }
  }

  /// The same for every kind of pair: u is the tangential part of the
  /// step's relative displacement of the first primitive's closest point
  /// against the second's, sum_k w_k (x_k - x_k^saved) with the lagged
  /// weights, and each point k takes w_k times the force.
  Tensor<1, 3> Contact::add_friction(const NormalForce &lagged,
                                     bool               with_tangent,
                                     model::DofBlock   &block)
  {
    const Pair  &pair = lagged.pair;
    const double mu   = friction_coefficient(pair);
    const double eps  = smoothing_length();
    Tensor<1, 3> at;
    if (!(eps > 0) || lagged.force == 0)
      return at;
    const Tensor<1, 3>            normal = lagged.normal / lagged.normal.norm();
    const std::array<Point<3>, 4> points =
        pair_points(pair, positions_, other_side(pair));
    const std::array<Point<3>, 4> before =
        pair_points(pair, saved_positions_, saved_other_side(pair));
    const std::array<double, 4> w =
        closest_point_weights(pair.edge_edge, lagged.closest);
    Tensor<1, 3> relative;
    for (unsigned int k = 0; k < 4; ++k)
      relative += w[k] * (points[k] - before[k]);
    const Tensor<1, 3> u      = relative - (relative * normal) * normal;
    const auto [ratio, slope] = friction_ratio(u.norm(), eps);
    const double dissipated = mu * lagged.force * friction_work(u.norm(), eps);
    friction_dissipation_ += dissipated;
    if (!pair.self)
      friction_dissipation_per_obstacle_[pair.obstacle] += dissipated;
    // On the first primitive's closest point; point k takes w_k of it.
    const Tensor<1, 3> force = -mu * lagged.force * ratio * u;

    const ShellCoordinates shell = shell_coordinates(pair);
    const unsigned int     first = shell.first / 3;
    const unsigned int     n     = (shell.last - shell.first) / 3;
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int c = 0; c < 3; ++c)
        block.vector[3 * i + c] += w[first + i] * force[c];
    if (!pair.self)
    {
      // The obstacle's share, applied at its closest point.
      ObstacleLoad &load = loads_[pair.obstacle];
      Tensor<1, 3>  reaction;
      for (unsigned int k = 0; k < 4; ++k)
        if (on_obstacle(pair, k))
        {
          reaction += w[k] * force;
          at += std::abs(w[k]) * points[k];
        }
      load.force += reaction;
      load.moment += cross_product_3d(at, reaction);
    }
    if (with_tangent)
      add_friction_tangent(w, first, n, mu * lagged.force, {ratio, slope}, u,
                           normal, block.matrix);
    return at;
  }
} // namespace coshell::contact
