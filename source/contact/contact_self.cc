// Self contact: shell vertices against shell triangles, with the same
// barrier or penalty as against obstacles. What is particular to it: which
// pairs count (not a triangle's own corners, not neighbours closer than
// the shell is thick), the step filter with both sides moving, and the
// couplings the tangent needs beyond the mesh's own.

#include <coshell/contact/ccd.h>
#include <coshell/contact/contact.h>
#include <coshell/contact/distances.h>

#include <algorithm>
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

    unsigned int root_of(std::vector<unsigned int> &parent, unsigned int v)
    {
      while (parent[v] != v)
        v = parent[v] = parent[parent[v]];
      return v;
    }
  } // namespace

  void Contact::exclude_reference_neighbours()
  {
    // Connected pieces by union-find over the triangles' corners.
    std::vector<unsigned int> piece(model_.surface().n_vertices());
    std::iota(piece.begin(), piece.end(), 0u);
    for (const auto &t : shell_triangles_)
      for (unsigned int i = 1; i < 3; ++i)
        piece[root_of(piece, t[i])] = root_of(piece, t[0]);
    const auto &X    = model_.surface().get_vertices();
    const Tree  tree = shell_triangle_tree(
         X, nullptr, parameters_.self_exclusion * largest_thickness_);
    excluded_.assign(X.size(), {});
    Hits hits;
    for (const unsigned v : shell_vertices_)
    {
      hits.clear();
      tree.query(bgi::intersects(box_of({X[v]}, 0)), std::back_inserter(hits));
      for (const auto &hit : hits)
      {
        const auto &t = shell_triangles_[hit.second];
        if (root_of(piece, v) != root_of(piece, t[0]))
          continue;
        const double reference = std::sqrt(
            point_triangle_distance(X[v], X[t[0]], X[t[1]], X[t[2]], false)
                .value);
        if (reference < parameters_.self_exclusion * self_offset(v, hit.second))
          excluded_[v].push_back(hit.second);
      }
      std::sort(excluded_[v].begin(), excluded_[v].end());
    }
    if (parameters_.edge_edge_pairs)
    {
      std::vector<unsigned int> roots(piece.size());
      for (unsigned int v = 0; v < piece.size(); ++v)
        roots[v] = root_of(piece, v);
      exclude_reference_edge_neighbours(roots);
    }
  }

  void Contact::exclude_reference_edge_neighbours(
      const std::vector<unsigned int> &piece_of_vertex)
  {
    const auto &X    = model_.surface().get_vertices();
    const Tree  tree = shell_triangle_tree(
         X, nullptr, parameters_.self_exclusion * largest_thickness_);
    excluded_edges_.assign(shell_edges_.size(), {});
    std::vector<unsigned int> near;
    EdgeMarks                 marks(shell_edges_.size());
    for (unsigned int e = 0; e < shell_edges_.size(); ++e)
    {
      const auto [a, b] = shell_edges_[e];
      edges_near(tree, shell_triangle_edges_, marks, {X[a], X[b]}, 0, near);
      for (const unsigned f : near)
      {
        const auto [c, d] = shell_edges_[f];
        if (piece_of_vertex[a] != piece_of_vertex[c])
          continue;
        const double reference = std::sqrt(
            segment_segment_distance(X[a], X[b], X[c], X[d], false).value);
        if (reference < parameters_.self_exclusion * self_edge_offset(e, f))
          excluded_edges_[e].push_back(f);
      }
      std::sort(excluded_edges_[e].begin(), excluded_edges_[e].end());
    }
  }

  double Contact::self_edge_offset(unsigned int e, unsigned int f) const
  {
    double sum = 0;
    for (const unsigned int edge : {e, f})
      for (const unsigned int v : shell_edges_[edge])
        sum += vertex_thickness(v);
    return sum / 4; // the mean of the two edges' half thicknesses, summed
  }

  double Contact::self_reach(unsigned int v, double activation) const
  {
    return 0.5 * (vertex_thickness(v) + largest_current_thickness()) +
           activation;
  }

  double Contact::self_edge_reach(unsigned int e, double activation) const
  {
    const auto [a, b] = shell_edges_[e];
    return 0.25 * (vertex_thickness(a) + vertex_thickness(b)) +
           0.5 * largest_current_thickness() + activation;
  }

  double Contact::self_offset(unsigned int v, unsigned int t) const
  {
    return 0.5 * (vertex_thickness(v) + triangle_thickness(t));
  }

  const std::vector<Point<3>> &Contact::other_side(const Pair &pair) const
  {
    return pair.self ? positions_ : current_[pair.obstacle];
  }

  const std::vector<Point<3>> &Contact::saved_other_side(const Pair &pair) const
  {
    return pair.self ? saved_positions_ : saved_[pair.obstacle];
  }
} // namespace coshell::contact
