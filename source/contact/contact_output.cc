#include <coshell/base/parallel_environment.h>
#include <coshell/contact/contact.h>

#include <cmath>
#include <fstream>
#include <iomanip>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>
#include <tuple>

namespace coshell::contact
{
  using namespace dealii;

  Vector<double> Contact::vertex_fields() const
  {
    Vector<double> fields(model_.n_dofs());
    for (const unsigned v : shell_vertices_)
    {
      const auto  &dofs = model_.vertex_dofs(v);
      Tensor<1, 3> force;
      for (unsigned int c = 0; c < 3; ++c)
        force[c] = fields[dofs[c]] = vertex_force_[dofs[c]];
      // Out of reach: the gap is at least the activation distance.
      fields[dofs[3]] =
          std::isfinite(vertex_gap_[v]) ? vertex_gap_[v] : activation_;
      fields[dofs[4]] = force.norm() / shell_vertex_area_[v];
    }
    return fields;
  }

  void Contact::write_obstacles_vtu(const std::string &file) const
  {
    if (!base::writes_output())
      return;
    std::ofstream out(file);
    if (!out)
      throw std::runtime_error("cannot write '" + file + "'");
    unsigned int n_points = 0, n_cells = 0;
    for (unsigned int o = 0; o < current_.size(); ++o)
    {
      n_points += current_[o].size();
      n_cells += parameters_.obstacles[o].triangles.size();
    }
    out << std::setprecision(10)
        << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" "
           "version=\"0.1\">\n<UnstructuredGrid>\n<Piece NumberOfPoints=\""
        << n_points << "\" NumberOfCells=\"" << n_cells
        << "\">\n<Points>\n<DataArray type=\"Float64\" "
           "NumberOfComponents=\"3\" format=\"ascii\">\n";
    for (const auto &points : current_)
      for (const auto &p : points)
        out << p[0] << ' ' << p[1] << ' ' << p[2] << '\n';
    out << "</DataArray>\n</Points>\n<Cells>\n<DataArray type=\"Int64\" "
           "Name=\"connectivity\" format=\"ascii\">\n";
    unsigned int first = 0;
    for (unsigned int o = 0; o < current_.size(); ++o)
    {
      for (const auto &t : parameters_.obstacles[o].triangles)
        out << first + t[0] << ' ' << first + t[1] << ' ' << first + t[2]
            << '\n';
      first += current_[o].size();
    }
    out << "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" "
           "format=\"ascii\">\n";
    for (unsigned int k = 1; k <= n_cells; ++k)
      out << 3 * k << '\n';
    out << "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" "
           "format=\"ascii\">\n";
    for (unsigned int k = 0; k < n_cells; ++k)
      out << "5\n";
    out << "</DataArray>\n</Cells>\n<CellData Scalars=\"obstacle\">\n"
           "<DataArray type=\"Int32\" Name=\"obstacle\" format=\"ascii\">\n";
    for (unsigned int o = 0; o < current_.size(); ++o)
      for (unsigned int k = 0; k < parameters_.obstacles[o].triangles.size();
           ++k)
        out << o + 1 << '\n';
    out << "</DataArray>\n</CellData>\n</Piece>\n</UnstructuredGrid>\n"
           "</VTKFile>\n";
    if (!out)
      throw std::runtime_error("cannot write '" + file + "'");
  }

  ContactContribution::ContactContribution(Contact &contact) : contact_(contact)
  {
  }

  std::string ContactContribution::name() const
  {
    return "contact";
  }

  model::ForceKind ContactContribution::kind() const
  {
    return model::ForceKind::contact;
  }

  bool ContactContribution::has_cell_terms() const
  {
    return false;
  }

  void ContactContribution::add_blocks(const model::EvaluationPoint &point,
                                       const model::BlockSink       &sink,
                                       bool with_tangent)
  {
    contact_.add_pair_terms(point.state, sink, with_tangent);
  }

  void ContactContribution::prepare(const model::EvaluationPoint &point)
  {
    contact_.prepare(point.state, point.time);
  }

  std::uint64_t ContactContribution::update_coupled_vertices(
      const model::EvaluationPoint &point) const
  {
    return contact_.update_self_couplings(point.state);
  }

  void ContactContribution::coupled_vertices(
      std::vector<std::array<unsigned int, 2>> &pairs) const
  {
    const auto &couplings = contact_.self_couplings();
    pairs.insert(pairs.end(), couplings.begin(), couplings.end());
  }

  bool ContactContribution::couples_beyond_cells() const
  {
    return contact_.self_contact();
  }

  bool ContactContribution::pending() const
  {
    return contact_.obstacles_pending();
  }

  double ContactContribution::admissible_fraction(
      const model::ShellState &state, const Vector<double> &correction) const
  {
    return contact_.admissible_fraction(state, correction);
  }

  void ContactContribution::save()
  {
    contact_.save();
  }

  void ContactContribution::restore()
  {
    contact_.restore();
  }

  void ContactContribution::begin_trial()
  {
    contact_.begin_trial();
  }

  void ContactContribution::end_trial()
  {
    contact_.end_trial();
  }

  void
  ContactContribution::extrapolate_reports(const Vector<double> &correction)
  {
    contact_.extrapolate_loads(correction);
  }

  bool ContactContribution::symmetric_tangent() const
  {
    return true;
  }

  bool ContactContribution::has_potential() const
  {
    return true;
  }

  double
  ContactContribution::global_energy(const model::EvaluationPoint &) const
  {
    return contact_.potential() + contact_.step_friction_dissipation();
  }

  bool ContactContribution::use_convex_tangent()
  {
    return contact_.use_projected_tangent();
  }

  std::string ContactContribution::failure_context() const
  {
    return contact_.squeeze_report() + contact_.friction_report();
  }

  /// The shell vertex a pair's gap is charged to: its point, or the first
  /// vertex of its shell triangle or edge.
  unsigned int Contact::pair_shell_vertex(const Pair &pair) const
  {
    if (pair.edge_edge)
      return shell_edges_[pair.shell][0];
    return pair.shell_vertex_side ? pair.shell
                                  : shell_triangles_[pair.shell][0];
  }

  std::map<unsigned int, std::map<unsigned int, double>>
  Contact::obstacle_gaps_by_vertex() const
  {
    std::map<unsigned int, std::map<unsigned int, double>> gaps;
    for (const Pair &pair : pairs_)
    {
      if (pair.self)
        continue;
      const auto   points = pair_points(pair, positions_, other_side(pair));
      const double gap =
          std::sqrt(pair_distance(pair, points, false).value) - offset(pair);
      auto [it, added] =
          gaps[pair_shell_vertex(pair)].emplace(pair.obstacle, gap);
      if (!added)
        it->second = std::min(it->second, gap);
    }
    return gaps;
  }

  std::string Contact::squeeze_report() const
  {
    constexpr double infinity = std::numeric_limits<double>::infinity();
    // Squeezed: both gaps below a tenth of the activation distance, where
    // the barrier pushes with many times its force at half of it.
    const double squeezed    = 0.1 * activation_;
    double       nearest_gap = infinity, pinch_gap = infinity;
    unsigned int nearest_vertex = 0, nearest_obstacle = 0, pinch_vertex = 0;
    std::array<unsigned int, 2> pinch_obstacles{};
    std::array<double, 2>       pinch_gaps{};
    for (const auto &[vertex, by_obstacle] : obstacle_gaps_by_vertex())
      for (const auto &[o, gap] : by_obstacle)
      {
        if (gap < nearest_gap)
          std::tie(nearest_gap, nearest_vertex, nearest_obstacle) =
              std::tuple(gap, vertex, o);
        for (const auto &[other, other_gap] : by_obstacle)
        {
          const double larger = std::max(gap, other_gap);
          if (other > o && larger < squeezed && larger < pinch_gap)
          {
            pinch_gap       = larger;
            pinch_vertex    = vertex;
            pinch_obstacles = {o, other};
            pinch_gaps      = {gap, other_gap};
          }
        }
      }
    if (nearest_gap == infinity)
      return "";
    const auto name = [this](unsigned int o)
    { return "'" + parameters_.obstacles[o].name + "'"; };
    std::ostringstream out;
    out << std::setprecision(3);
    if (pinch_gap < infinity)
      out << "; the shell is pinched between obstacles "
          << name(pinch_obstacles[0]) << " and " << name(pinch_obstacles[1])
          << " at vertex " << pinch_vertex << " (" << positions_[pinch_vertex]
          << "), gaps " << pinch_gaps[0] << " and " << pinch_gaps[1]
          << " (length units): a jam, they leave it no room to move";
    else
      out << "; the smallest gap, " << nearest_gap
          << " (length units), is between shell vertex " << nearest_vertex
          << " (" << positions_[nearest_vertex] << ") and obstacle "
          << name(nearest_obstacle);
    pair_potential_->explain_jam(out, nearest_gap);
    return out.str();
  }
} // namespace coshell::contact
