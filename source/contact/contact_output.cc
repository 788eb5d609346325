#include <coshell/contact/contact.h>
#include <coshell/solvers/parallel_environment.h>

#include <cmath>
#include <fstream>
#include <iomanip>
#include <stdexcept>

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
    if (!solvers::writes_output())
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

  void ContactContribution::coupled_vertices(
      const model::EvaluationPoint             &point,
      std::vector<std::array<unsigned int, 2>> &pairs) const
  {
    contact_.self_couplings(point.state, pairs);
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

  bool ContactContribution::symmetric_tangent() const
  {
    return true;
  }
} // namespace coshell::contact
