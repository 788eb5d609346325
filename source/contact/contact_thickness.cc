// Contact with a shell whose thickness changes (Element/Thickness stretch,
// doc/theory.md section 21): offsets of half the current thickness, their
// derivatives in the vertex stretches, and the step filter's bound on a
// thickening.

#include <coshell/contact/contact.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace coshell::contact
{
  using namespace dealii;

  namespace
  {
    // Of the gap the step filter keeps against the motion (a tenth,
    // additive_ccd), the share a pair's thickening may take, so that a
    // hundredth of the gap is left at any fraction of the correction.
    constexpr double thickening_share = 0.09;
  } // namespace

  double Contact::vertex_thickness(unsigned int v) const
  {
    if (stretch_.empty())
      return model_.vertex_thickness(v);
    return model_.vertex_thickness(v) * stretch_[v];
  }

  double Contact::triangle_thickness(unsigned int t) const
  {
    if (stretch_.empty())
      return shell_triangle_thickness_[t];
    double mean = 0;
    for (const unsigned int v : shell_triangles_[t])
      mean += stretch_[v] / 3;
    return shell_triangle_thickness_[t] * mean;
  }

  double Contact::largest_current_thickness() const
  {
    return largest_thickness_ * largest_stretch_;
  }

  void Contact::update_stretches(const model::ShellState &state)
  {
    if (!model_.has_thickness_stretch())
      return;
    stretch_.assign(model_.surface().n_vertices(), 1.0);
    largest_stretch_ = 1;
    for (const unsigned int v : shell_vertices_)
    {
      stretch_[v]      = model_.thickness_stretch(v, state.values());
      largest_stretch_ = std::max(largest_stretch_, stretch_[v]);
    }
  }

  double Contact::offset_growth_since(const std::vector<double> &before) const
  {
    if (stretch_.empty())
      return 0;
    // Lists made before the stretches were read: nothing is known.
    if (before.size() != stretch_.size())
      return std::numeric_limits<double>::infinity();
    double largest = 0;
    for (const unsigned int v : shell_vertices_)
      largest = std::max(largest, stretch_[v] - before[v]);
    return largest_thickness_ * largest;
  }

  unsigned int Contact::offset_slopes(const Pair                  &pair,
                                      std::array<unsigned int, 4> &vertices,
                                      std::array<double, 4>       &slopes) const
  {
    // offset = h_v / 2 (vertex), h_t mean(lambda) / 2 (triangle), the
    // mean of two vertex offsets (edge); self pairs sum both sides' halves
    // (vertex-triangle) or take the mean of four (edge-edge).
    const auto add = [&](unsigned int n, unsigned int v, double slope)
    {
      vertices[n] = v;
      slopes[n]   = slope;
      return n + 1;
    };
    const auto triangle = [&](unsigned int n, unsigned int t)
    {
      for (const unsigned int v : shell_triangles_[t])
        n = add(n, v, shell_triangle_thickness_[t] / 6);
      return n;
    };
    unsigned int n = 0;
    if (pair.edge_edge)
    {
      for (const unsigned int e : {pair.shell, pair.other})
      {
        for (const unsigned int v : shell_edges_[e])
          n = add(n, v, 0.25 * model_.vertex_thickness(v));
        if (!pair.self)
          break;
      }
      return n;
    }
    if (pair.self)
      return triangle(
          add(0, pair.shell, 0.5 * model_.vertex_thickness(pair.shell)),
          pair.other);
    if (pair.shell_vertex_side)
      return add(0, pair.shell, 0.5 * model_.vertex_thickness(pair.shell));
    return triangle(0, pair.shell);
  }

  void Contact::add_stretch_terms(const Pair                    &pair,
                                  const std::array<Point<3>, 4> &points,
                                  const SquaredDistance         &s,
                                  double                         weight,
                                  const ScalarDerivatives       &phi,
                                  const PairEnergy              &energy,
                                  const model::DofBlock         &translations,
                                  const model::BlockSink        &sink,
                                  bool with_tangent) const
  {
    std::array<unsigned int, 4> vertices;
    std::array<double, 4>       slopes;
    const unsigned int          n = offset_slopes(pair, vertices, slopes);
    const unsigned int          m = translations.dofs.size();
    model::DofBlock             block;
    block.dofs = translations.dofs;
    for (unsigned int i = 0; i < n; ++i)
      block.dofs.push_back(model_.thickness_dof(vertices[i]));
    block.vector.reinit(m + n);
    // E = w m phi(g), dg/dlambda_i = -slope_i: r_i = -dE/dlambda_i.
    const double force = weight * energy.mollifier * phi.first;
    for (unsigned int i = 0; i < n; ++i)
      block.vector[m + i] = force * slopes[i];
    const bool anticipating = pending_ && !pair.self;
    if (!with_tangent && !anticipating)
    {
      sink(block);
      return;
    }
    // d(w m phi')/dx: the pair energy of phi' in place of phi.
    const PairEnergy slope_of_force =
        pair_energy(pair, points, s, weight, {phi.first, phi.second, 0}, false);
    const auto shell = shell_coordinates(pair);
    if (anticipating)
    {
      // As anticipate_obstacle() for the translations: -K_lambda,X dX, so
      // the next correction already thins the shell in the held-back
      // obstacle's way (K_lambda,X = -slope d(w m phi')/dX).
      const auto remaining = remaining_obstacle_moves(pair);
      for (unsigned int i = 0; i < n; ++i)
        for (unsigned int j = 0; j < 12; ++j)
          if (j < shell.first || j >= shell.last)
            block.vector[m + i] += slopes[i] * slope_of_force.gradient[j] *
                                   remaining[j / 3][j % 3];
    }
    if (with_tangent)
      stretch_tangent({slopes.begin(), slopes.begin() + n},
                      slope_of_force.gradient, shell,
                      weight * energy.mollifier * phi.second, block.matrix);
    sink(block);
  }

  void Contact::stretch_tangent(const std::vector<double>  &slopes,
                                const Coordinates12        &slope_of_force,
                                ShellCoordinates            shell,
                                double                      curvature,
                                dealii::FullMatrix<double> &matrix)
  {
    // d2E/dx dlambda_i = -slope_i d(w m phi')/dx and
    // d2E/dlambda_i dlambda_k = w m phi'' slope_i slope_k, after the
    // translations' rows (shell.last - shell.first of them).
    const unsigned int m = shell.last - shell.first, n = slopes.size();
    matrix.reinit(m + n, m + n);
    for (unsigned int i = 0; i < n; ++i)
    {
      for (unsigned int j = shell.first; j < shell.last; ++j)
      {
        const double coupling          = -slopes[i] * slope_of_force[j];
        matrix(m + i, j - shell.first) = coupling;
        matrix(j - shell.first, m + i) = coupling;
      }
      for (unsigned int k = 0; k < n; ++k)
        matrix(m + i, m + k) = curvature * slopes[i] * slopes[k];
    }
  }

  double Contact::thickening_fraction(const Vector<double> &correction) const
  {
    if (stretch_.empty())
      return 1;
    // Pairs within reach: each may lose to its offset's growth at most
    // thickening_share of its own gap, of which the step filter keeps a
    // tenth against the motion.
    double fraction = 1;
    for (const Pair &pair : pairs_)
    {
      std::array<unsigned int, 4> vertices;
      std::array<double, 4>       slopes;
      const unsigned int          n = offset_slopes(pair, vertices, slopes);
      double                      growth = 0;
      for (unsigned int i = 0; i < n; ++i)
        growth += slopes[i] *
                  std::max(correction[model_.thickness_dof(vertices[i])], 0.0);
      if (growth == 0)
        continue;
      const auto   points = pair_points(pair, positions_, other_side(pair));
      const double gap =
          std::sqrt(pair_distance(pair, points, false).value) - offset(pair);
      fraction = std::min(fraction, thickening_share * gap / growth);
    }
    // Pairs out of reach keep at least the activation distance d.
    double largest_growth = 0;
    for (const unsigned int v : shell_vertices_)
      largest_growth =
          std::max(largest_growth, correction[model_.thickness_dof(v)]);
    largest_growth *= largest_thickness_; // both sides' halves, at most
    if (largest_growth > 0)
      fraction =
          std::min(fraction, thickening_share * activation_ / largest_growth);
    return fraction;
  }
} // namespace coshell::contact
