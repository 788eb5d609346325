#include <coshell/model/quantities.h>

#include <limits>

#include <coshell/base/constants.h>

#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/utilities.h>
#include <deal.II/lac/lapack_full_matrix.h>

#include <algorithm>
#include <cmath>
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
                      "component is ux, uy, uz, rx, ry or rz. Unit: length "
                      "for x y z (m in SI, mm in the IOL scenes); the "
                      "value in its component's (length for ux, uy, uz, "
                      "rad for rx, ry, rz).");
    prm.declare_entry("Maximum values", "", Patterns::Anything(),
                      "Largest-magnitude nodal value of a component over the "
                      "mesh (sign kept), as 'name: component' entries "
                      "separated by ';'. Unit: the component's (length "
                      "for ux, uy, uz, rad for rx, ry, rz).");
    prm.declare_entry(
        "Region poses", "", Patterns::Anything(),
        "Where a region of the shell (a material id: the optic of a lens) "
        "sits against an axis (a capsular bag's), as 'name: region cx cy "
        "cz ax ay az' entries separated by ';': the axis through the "
        "centre (cx, cy, cz) along (ax, ay, az); each "
        "number may be an expression of the scene's Constants (no blanks "
        "inside). Gives name_decentration, the distance of the region's "
        "vertex centroid from the axis (length), name_axial, its position "
        "along the axis from the centre (length), and name_tilt, the angle "
        "between the axis and the normal of the plane fitted to the "
        "region's vertices by least squares (degrees, 0 to 90), and "
        "name_shape_deviation, the largest distance of a vertex of the "
        "region from the rigid motion of its reference shape that fits "
        "it best in least squares (how far the region is deformed). "
        "Unit: length for cx cy cz (m in SI, mm in the IOL scenes), "
        "dimensionless for ax ay az.");
    prm.declare_entry("Reference values", "",
                      Patterns::Map(Patterns::Anything(), Patterns::Double()),
                      "Reference value per quantity name ('name: value, "
                      "...'); summary.json then reports the relative "
                      "error. Unit: each value in its quantity's unit "
                      "(length for ux, uy, uz, rad for rx, ry, rz).");
    prm.declare_entry("Reference curves", "", Patterns::Anything(),
                      "Reference load-displacement points for nonlinear "
                      "runs, as 'name: factor value, factor value, ...' "
                      "entries separated by ';'. Load control stops "
                      "exactly at these load factors; the points are "
                      "written to reference_points.csv and plotted. Unit: "
                      "dimensionless for factor (the load factor); value "
                      "in its quantity's unit (length for ux, uy, uz, rad "
                      "for rx, ry, rz).");
    prm.declare_entry("Largest strains", "false", Patterns::Bool(),
                      "Dynamic runs: also write, per step, the largest "
                      "principal membrane strain and the largest bending "
                      "strain at the surfaces (h/2 times the principal "
                      "curvature) over the cells, as max_membrane_strain "
                      "and max_bending_strain, and the largest principal "
                      "strain at either surface (the two as tensors "
                      "summed) as max_surface_strain (dimensionless), "
                      "from the "
                      "stress resultants and the cell's material.");
    prm.leave_subsection();
  }

  void QuantitiesOfInterest::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Quantities of interest");
    const std::string points     = prm.get("Point values");
    const std::string maxima     = prm.get("Maximum values");
    const std::string poses      = prm.get("Region poses");
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
    parse_region_poses(poses);
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

  void QuantitiesOfInterest::parse_region_poses(const std::string &text)
  {
    const std::string where = "Quantities of interest/Region poses";
    region_poses_.clear();
    for (const auto &[name, spec] : named_entries(text, "Region poses"))
    {
      std::istringstream  in(spec);
      std::vector<double> numbers;
      for (std::string token; in >> token;)
        numbers.push_back(base::evaluate_constant_expression(
            token, base::expression_constants(), where + ": " + name));
      const bool malformed = numbers.size() != 7 || numbers[0] < 0 ||
                             numbers[0] != std::floor(numbers[0]);
      const Tensor<1, 3> axis =
          malformed ? Tensor<1, 3>()
                    : Tensor<1, 3>({numbers[4], numbers[5], numbers[6]});
      if (axis.norm() == 0)
        throw std::invalid_argument(
            where + ": '" + spec +
            "' is not 'region cx cy cz ax ay az' (a material id, a point "
            "and a non-zero direction)");
      region_poses_.push_back({name, static_cast<unsigned int>(numbers[0]),
                               Point<3>(numbers[1], numbers[2], numbers[3]),
                               axis / axis.norm()});
    }
  }

  namespace
  {
    /// The vertices of the cells of one material id, each once.
    std::vector<unsigned int> region_vertices(const mesh::Surface &surface,
                                              unsigned int         region)
    {
      std::vector<bool> in_region(surface.n_vertices(), false);
      for (const auto &cell : surface.active_cell_iterators())
        if (cell->material_id() == region)
          for (const unsigned int v : cell->vertex_indices())
            in_region[cell->vertex_index(v)] = true;
      std::vector<unsigned int> vertices;
      for (unsigned int v = 0; v < surface.n_vertices(); ++v)
        if (in_region[v])
          vertices.push_back(v);
      return vertices;
    }

    Point<3> centroid_of(const std::vector<Point<3>> &points)
    {
      Point<3> centroid;
      for (const auto &x : points)
        centroid += x / static_cast<double>(points.size());
      return centroid;
    }

    /// Largest distance of 'current' from the rigid motion of 'reference'
    /// that fits it best in least squares (Kabsch: the rotation V D U^T
    /// from the SVD U S V^T of the cross-covariance, D turning a
    /// reflection into a rotation).
    double rigid_fit_deviation(const std::vector<Point<3>> &reference,
                               const std::vector<Point<3>> &current)
    {
      const Point<3>           from = centroid_of(reference);
      const Point<3>           to   = centroid_of(current);
      LAPACKFullMatrix<double> covariance(3, 3);
      for (unsigned int i = 0; i < reference.size(); ++i)
        for (unsigned int j = 0; j < 3; ++j)
          for (unsigned int k = 0; k < 3; ++k)
            covariance(j, k) +=
                (reference[i][j] - from[j]) * (current[i][k] - to[k]);
      covariance.compute_svd();
      Tensor<2, 3> u, v;
      for (unsigned int j = 0; j < 3; ++j)
        for (unsigned int k = 0; k < 3; ++k)
        {
          u[j][k] = covariance.get_svd_u()(j, k);
          v[j][k] = covariance.get_svd_vt()(k, j);
        }
      Tensor<2, 3> reflection     = unit_symmetric_tensor<3>();
      reflection[2][2]            = determinant(v * transpose(u)) < 0 ? -1 : 1;
      const Tensor<2, 3> rotation = v * reflection * transpose(u);
      double             largest  = 0;
      for (unsigned int i = 0; i < reference.size(); ++i)
        largest = std::max(
            largest,
            (rotation * (reference[i] - from) - (current[i] - to)).norm());
      return largest;
    }
  } // namespace

  void
  QuantitiesOfInterest::add_region_pose(const RegionPose              &pose,
                                        const ShellModel              &model,
                                        const Vector<double>          &solution,
                                        std::map<std::string, double> &values)
  {
    const auto &surface  = model.surface();
    const auto  vertices = region_vertices(surface, pose.region);
    if (vertices.size() < 3)
      throw std::runtime_error(
          "Quantities of interest/Region poses: " + pose.name +
          ": the mesh has fewer than three vertices in region " +
          std::to_string(pose.region));
    std::vector<Point<3>> reference, positions;
    for (const unsigned int v : vertices)
    {
      reference.push_back(surface.get_vertices()[v]);
      positions.push_back(reference.back() +
                          vertex_block(solution, model.vertex_dofs(v), ux));
    }
    const Point<3>        centroid = centroid_of(positions);
    SymmetricTensor<2, 3> scatter;
    for (const auto &x : positions)
      scatter += symmetrize(outer_product(x - centroid, x - centroid));
    // Eigenvectors come by decreasing eigenvalue: the last is the normal
    // of the least-squares plane.
    const Tensor<1, 3> normal           = eigenvectors(scatter)[2].second;
    const Tensor<1, 3> offset           = centroid - pose.centre;
    const double       axial            = offset * pose.axis;
    values[pose.name + "_decentration"] = (offset - axial * pose.axis).norm();
    values[pose.name + "_axial"]        = axial;
    values[pose.name + "_tilt"] =
        std::acos(std::min(1.0, std::abs(normal * pose.axis))) * 180 /
        numbers::PI;
    values[pose.name + "_shape_deviation"] =
        rigid_fit_deviation(reference, positions);
  }

  void QuantitiesOfInterest::check_defined(const std::string &name,
                                           const std::string &parameter) const
  {
    bool known = false;
    for (const auto &p : point_values_)
      known = known || p.name == name;
    for (const auto &m : maximum_values_)
      known = known || m.name == name;
    for (const auto &pose : region_poses_)
      for (const char *measure :
           {"_decentration", "_axial", "_tilt", "_shape_deviation"})
        known = known || pose.name + measure == name;
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
    for (const auto &pose : region_poses_)
      add_region_pose(pose, model, solution, values);
    if (model.has_thickness_stretch())
      add_thickness_extremes(model, solution, values);
    return values;
  }

  void QuantitiesOfInterest::add_thickness_extremes(
      const ShellModel              &model,
      const Vector<double>          &solution,
      std::map<std::string, double> &values)
  {
    double smallest_stretch = std::numeric_limits<double>::max();
    double largest_stretch  = 0;
    for (unsigned int v = 0; v < model.surface().n_vertices(); ++v)
      if (model.vertex_is_used(v))
      {
        const double stretch = model.thickness_stretch(v, solution);
        smallest_stretch     = std::min(smallest_stretch, stretch);
        largest_stretch      = std::max(largest_stretch, stretch);
      }
    double thinnest = std::numeric_limits<double>::max();
    for (const auto &cell : model.dof_handler().active_cell_iterators())
      thinnest = std::min(thinnest, model.current_thickness(cell, solution));
    values["min_thickness_stretch"] = smallest_stretch;
    values["max_thickness_stretch"] = largest_stretch;
    values["min_thickness"]         = thinnest;
  }

  const std::map<std::string, double> &QuantitiesOfInterest::references() const
  {
    return references_;
  }
} // namespace coshell::model
