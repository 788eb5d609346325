#include <coshell/model/quantities.h>

#include <deal.II/base/utilities.h>

#include <algorithm>
#include <sstream>
#include <stdexcept>

namespace coshell::model
{
  using namespace dealii;

  namespace
  {
    /// Splits "name: rest; name: rest" into (name, rest) pairs.
    std::vector<std::pair<std::string, std::string>>
    named_entries(const std::string &text, const std::string &parameter)
    {
      std::vector<std::pair<std::string, std::string>> entries;
      for (const auto &entry : Utilities::split_string_list(text, ';'))
      {
        const auto colon = entry.find(':');
        if (colon == std::string::npos || colon == 0)
          throw std::invalid_argument("Quantities of interest/" + parameter +
                                      ": entry '" + entry +
                                      "' is not of the form 'name: ...'");
        entries.emplace_back(Utilities::trim(entry.substr(0, colon)),
                             Utilities::trim(entry.substr(colon + 1)));
      }
      return entries;
    }
  } // namespace

  void QuantitiesOfInterest::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Quantities of interest");
    prm.declare_entry("Point values", "", Patterns::Anything(),
                      "Nodal values at the vertex nearest a point, as "
                      "'name: x y z component' entries separated by ';'; "
                      "x y z in length units of the scene (m, mm, ...); "
                      "component is ux, uy, uz, rx, ry or rz. The value is "
                      "in the unit of its component: length for ux, uy, "
                      "uz, rad for rx, ry, rz.");
    prm.declare_entry("Maximum values", "", Patterns::Anything(),
                      "Largest-magnitude nodal value of a component over the "
                      "mesh (sign kept), as 'name: component' entries "
                      "separated by ';'. The value is in the unit of its "
                      "component: length for ux, uy, uz, rad for rx, ry, "
                      "rz.");
    prm.declare_entry("Reference values", "",
                      Patterns::Map(Patterns::Anything(), Patterns::Double()),
                      "Reference value per quantity name ('name: value, "
                      "...'), each in the unit of that quantity (length for "
                      "ux, uy, uz, rad for rx, ry, rz); summary.json then "
                      "reports the relative error (dimensionless).");
    prm.declare_entry("Reference curves", "", Patterns::Anything(),
                      "Reference load-displacement points for nonlinear "
                      "runs, as 'name: factor value, factor value, ...' "
                      "entries separated by ';'; factor is the load factor "
                      "(dimensionless), value is in the unit of the "
                      "quantity (length for ux, uy, uz, rad for rx, ry, "
                      "rz). Load control stops exactly at these load "
                      "factors; the points are written to "
                      "reference_points.csv and plotted.");
    prm.declare_entry("Largest strains", "false", Patterns::Bool(),
                      "Dynamic runs: also write, per step, the largest "
                      "principal membrane strain and the largest bending "
                      "strain at the surfaces (h/2 times the principal "
                      "curvature) over the cells, as max_membrane_strain "
                      "and max_bending_strain (dimensionless), from the "
                      "stress resultants and the cell's material.");
    prm.leave_subsection();
  }

  void QuantitiesOfInterest::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Quantities of interest");
    const std::string points     = prm.get("Point values");
    const std::string maxima     = prm.get("Maximum values");
    const std::string references = prm.get("Reference values");
    const std::string curves     = prm.get("Reference curves");
    largest_strains_             = prm.get_bool("Largest strains");
    prm.leave_subsection();

    point_values_.clear();
    for (const auto &[name, spec] : named_entries(points, "Point values"))
    {
      std::istringstream in(spec);
      double             x, y, z;
      std::string        component;
      if (!(in >> x >> y >> z >> component))
        throw std::invalid_argument("Quantities of interest/Point values: '" +
                                    spec + "' is not 'x y z component'");
      point_values_.push_back(
          {name, Point<3>(x, y, z), parse_component(component)});
    }
    maximum_values_.clear();
    for (const auto &[name, component] :
         named_entries(maxima, "Maximum values"))
      maximum_values_.push_back({name, parse_component(component)});
    references_.clear();
    for (const auto &entry : Utilities::split_string_list(references, ','))
    {
      const auto pair         = Utilities::split_string_list(entry, ':');
      references_[pair.at(0)] = Utilities::string_to_double(pair.at(1));
    }
    for (const auto &[name, value] : references_)
      check_defined(name, "Reference values");
    reference_curves_.clear();
    for (const auto &[name, points] : named_entries(curves, "Reference curves"))
    {
      check_defined(name, "Reference curves");
      for (const auto &point : Utilities::split_string_list(points, ','))
      {
        std::istringstream in(point);
        double             factor, value;
        if (!(in >> factor >> value))
          throw std::invalid_argument(
              "Quantities of interest/Reference curves: '" + point +
              "' is not 'load_factor value'");
        reference_curves_[name].emplace_back(factor, value);
      }
    }
  }

  void QuantitiesOfInterest::check_defined(const std::string &name,
                                           const std::string &parameter) const
  {
    bool known = false;
    for (const auto &p : point_values_)
      known = known || p.name == name;
    for (const auto &m : maximum_values_)
      known = known || m.name == name;
    if (!known)
      throw std::invalid_argument("Quantities of interest/" + parameter +
                                  " names '" + name +
                                  "', which is not a defined quantity");
  }

  const std::map<std::string, QuantitiesOfInterest::Curve> &
  QuantitiesOfInterest::reference_curves() const
  {
    return reference_curves_;
  }

  std::vector<double> QuantitiesOfInterest::reference_load_factors() const
  {
    std::vector<double> factors;
    for (const auto &[name, curve] : reference_curves_)
      for (const auto &[factor, value] : curve)
        factors.push_back(factor);
    std::sort(factors.begin(), factors.end());
    return factors;
  }

  std::map<std::string, double>
  QuantitiesOfInterest::evaluate(const ShellModel     &model,
                                 const Vector<double> &solution) const
  {
    std::map<std::string, double> values;
    for (const auto &p : point_values_)
      values[p.name] = solution[model.vertex_dofs(
          model.nearest_vertex(p.where))[p.component]];
    for (const auto &m : maximum_values_)
    {
      double extreme = 0;
      for (unsigned int v = 0; v < model.surface().n_vertices(); ++v)
        if (model.vertex_is_used(v))
        {
          const double value = solution[model.vertex_dofs(v)[m.component]];
          if (std::abs(value) > std::abs(extreme))
            extreme = value;
        }
      values[m.name] = extreme;
    }
    return values;
  }

  const std::map<std::string, double> &QuantitiesOfInterest::references() const
  {
    return references_;
  }
} // namespace coshell::model
