#include <coshell/model/boundary_conditions.h>

#include <deal.II/base/utilities.h>

#include <set>
#include <sstream>
#include <stdexcept>

namespace coshell::model
{
  using namespace dealii;

  namespace
  {
    Tensor<1, 3> unit_vector(unsigned int axis)
    {
      Tensor<1, 3> e;
      e[axis] = 1;
      return e;
    }

    const std::vector<Tensor<1, 3>> all_axes = {unit_vector(0), unit_vector(1),
                                                unit_vector(2)};

    /// Two unit vectors spanning the plane orthogonal to n.
    std::vector<Tensor<1, 3>> plane_basis(const Tensor<1, 3> &n)
    {
      const unsigned int smallest =
          std::abs(n[0]) <= std::abs(n[1])
              ? (std::abs(n[0]) <= std::abs(n[2]) ? 0 : 2)
              : (std::abs(n[1]) <= std::abs(n[2]) ? 1 : 2);
      Tensor<1, 3> t1 = cross_product_3d(n, unit_vector(smallest));
      t1 /= t1.norm();
      return {t1, cross_product_3d(n, t1) / n.norm()};
    }

    /// Directions held at zero at one vertex.
    struct FixedDirections
    {
      std::vector<Tensor<1, 3>> translations, rotations;
    };

    void append(std::vector<Tensor<1, 3>>       &to,
                const std::vector<Tensor<1, 3>> &directions)
    {
      to.insert(to.end(), directions.begin(), directions.end());
    }

    /// Directions that a condition fixes at a vertex of a boundary edge
    /// with unit tangent 'tangent' on a cell with unit normal 'normal'.
    FixedDirections directions_of(const BoundaryCondition &condition,
                                  const Tensor<1, 3>      &tangent,
                                  const Tensor<1, 3>      &normal)
    {
      using Type = BoundaryCondition::Type;
      FixedDirections fixed;
      switch (condition.type)
      {
      case Type::clamped:
        fixed.translations = all_axes;
        fixed.rotations    = all_axes;
        break;
      case Type::simply_supported_hard:
        fixed.translations = all_axes;
        fixed.rotations    = {cross_product_3d(tangent, normal)};
        break;
      case Type::simply_supported_soft:
        fixed.translations = all_axes;
        break;
      case Type::symmetry:
        fixed.translations = {condition.plane_normal};
        fixed.rotations    = plane_basis(condition.plane_normal);
        break;
      case Type::fixed_components:
        for (const Component c : condition.components)
          (c < 3 ? fixed.translations : fixed.rotations)
              .push_back(unit_vector(c % 3));
        break;
      case Type::free:
        break;
      }
      return fixed;
    }

    /// Orthonormal basis of the span of 'directions' (Gram-Schmidt).
    std::vector<Tensor<1, 3>>
    orthonormal_span(const std::vector<Tensor<1, 3>> &directions)
    {
      std::vector<Tensor<1, 3>> basis;
      for (Tensor<1, 3> d : directions)
      {
        for (const auto &q : basis)
          d -= (d * q) * q;
        if (d.norm() > 1e-8)
          basis.push_back(d / d.norm());
      }
      return basis;
    }

    unsigned int largest_entry(const Tensor<1, 3> &v)
    {
      unsigned int best = 0;
      for (unsigned int i = 1; i < 3; ++i)
        if (std::abs(v[i]) > std::abs(v[best]))
          best = i;
      return best;
    }

    void add_entry_if_nonzero(AffineConstraints<double> &constraints,
                              global_dof_index           row,
                              global_dof_index           column,
                              double                     value)
    {
      if (std::abs(value) > 1e-14)
        constraints.add_entry(row, column, value);
    }

    /// Constrains three DoFs x (a vector block of one vertex) so that
    /// x . q = 0 for every fixed direction q. With one direction the
    /// largest component of q is eliminated; with two, x must lie along
    /// m = q1 x q2 and the two smaller components of m are slaved.
    void constrain_block(const std::vector<Tensor<1, 3>>       &fixed,
                         const std::array<global_dof_index, 3> &dofs,
                         AffineConstraints<double>             &constraints)
    {
      const std::vector<Tensor<1, 3>> q = orthonormal_span(fixed);
      if (q.size() == 3)
        for (const auto dof : dofs)
          constraints.add_line(dof);
      else if (q.size() == 1)
      {
        const unsigned int p = largest_entry(q[0]);
        constraints.add_line(dofs[p]);
        for (unsigned int j = 0; j < 3; ++j)
          if (j != p)
            add_entry_if_nonzero(constraints, dofs[p], dofs[j],
                                 -q[0][j] / q[0][p]);
      }
      else if (q.size() == 2)
      {
        const Tensor<1, 3> m = cross_product_3d(q[0], q[1]);
        const unsigned int j = largest_entry(m);
        for (unsigned int i = 0; i < 3; ++i)
          if (i != j)
          {
            constraints.add_line(dofs[i]);
            add_entry_if_nonzero(constraints, dofs[i], dofs[j], m[i] / m[j]);
          }
      }
    }
  } // namespace

  BoundaryCondition parse_boundary_condition(const std::string &text)
  {
    using Type                       = BoundaryCondition::Type;
    const std::string condition_text = Utilities::trim(text);
    BoundaryCondition condition;
    if (condition_text == "clamped")
      condition.type = Type::clamped;
    else if (condition_text == "simply supported hard")
      condition.type = Type::simply_supported_hard;
    else if (condition_text == "simply supported soft")
      condition.type = Type::simply_supported_soft;
    else if (condition_text == "free")
      condition.type = Type::free;
    else if (condition_text.rfind("symmetry ", 0) == 0 &&
             condition_text.size() == 10 &&
             std::string("xyz").find(condition_text[9]) != std::string::npos)
    {
      condition.type         = Type::symmetry;
      condition.plane_normal = unit_vector(condition_text[9] - 'x');
    }
    else if (condition_text.rfind("fixed ", 0) == 0)
    {
      condition.type = Type::fixed_components;
      for (const auto &name :
           Utilities::split_string_list(condition_text.substr(6), ' '))
        if (!name.empty())
          condition.components.push_back(parse_component(name));
    }
    else
      throw std::invalid_argument(
          "unknown boundary condition '" + condition_text +
          "' (expected clamped, simply supported hard, simply supported soft, "
          "symmetry x|y|z, free, or fixed followed by components such as "
          "'fixed ux uz rx')");
    return condition;
  }

  void BoundaryConditions::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Boundary conditions");
    prm.declare_entry(
        "Conditions", "",
        Patterns::Map(Patterns::Integer(0), Patterns::Anything()),
        "Comma-separated 'boundary id: condition' pairs. Conditions: clamped "
        "(u = theta = 0); simply supported hard (u = 0 and no rotation about "
        "the in-plane edge normal); simply supported soft (u = 0); symmetry "
        "x|y|z (mirror plane with that normal); free; fixed <components> "
        "(e.g. 'fixed ux uz rx'). Example: 0: clamped, 1: symmetry x. "
        "The conditions hold the chosen displacements and rotations at "
        "zero. Unit: dimensionless (boundary ids).");
    prm.declare_entry(
        "Point conditions", "", Patterns::Anything(),
        "Conditions at the vertex nearest a point, as 'x y z : condition' "
        "entries separated by ';' (e.g. '0 0 10 : fixed uz' to stop a "
        "rigid translation of a self-equilibrated model). Unit: length for "
        "x y z (m in SI, mm in the IOL scenes).");
    prm.leave_subsection();
  }

  void BoundaryConditions::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Boundary conditions");
    const std::string text   = prm.get("Conditions");
    const std::string points = prm.get("Point conditions");
    prm.leave_subsection();
    point_conditions_.clear();
    for (const auto &entry : Utilities::split_string_list(points, ';'))
    {
      const auto         colon = entry.find(':');
      std::istringstream where(entry.substr(0, colon));
      Point<3>           point;
      if (colon == std::string::npos ||
          !(where >> point[0] >> point[1] >> point[2]))
        throw std::invalid_argument("Boundary conditions/Point conditions, "
                                    "entry '" +
                                    entry + "' is not 'x y z : condition'");
      point_conditions_.emplace_back(
          point, parse_boundary_condition(entry.substr(colon + 1)));
    }
    conditions_.clear();
    for (const auto &entry : Utilities::split_string_list(text, ','))
    {
      const auto key_value = Utilities::split_string_list(entry, ':');
      try
      {
        conditions_[Utilities::string_to_int(key_value.at(0))] =
            parse_boundary_condition(key_value.at(1));
      }
      catch (const std::exception &error)
      {
        throw std::invalid_argument("Boundary conditions/Conditions, entry '" +
                                    entry + "': " + error.what());
      }
    }
  }

  const std::map<unsigned int, BoundaryCondition> &
  BoundaryConditions::conditions() const
  {
    return conditions_;
  }

  BoundaryConditions
  BoundaryConditions::without(const std::vector<unsigned int> &ids) const
  {
    BoundaryConditions released = *this;
    for (const unsigned int id : ids)
      if (released.conditions_.erase(id) == 0)
        throw std::invalid_argument(
            "Release names boundary id " + std::to_string(id) +
            ", which has no condition in Boundary conditions/Conditions");
    return released;
  }

  void BoundaryConditions::make_constraints(
      const ShellModel &model, AffineConstraints<double> &constraints) const
  {
    std::map<unsigned int, FixedDirections> fixed_at_vertex;
    std::set<unsigned int>                  ids_in_mesh;
    for (const auto &cell : model.dof_handler().active_cell_iterators())
      for (unsigned int f = 0; f < cell->n_faces(); ++f)
      {
        if (!cell->at_boundary(f))
          continue;
        const auto face = cell->face(f);
        ids_in_mesh.insert(face->boundary_id());
        const auto condition = conditions_.find(face->boundary_id());
        if (condition == conditions_.end())
          continue;
        Tensor<1, 3> tangent = face->vertex(1) - face->vertex(0);
        tangent /= tangent.norm();
        const FixedDirections fixed =
            directions_of(condition->second, tangent, model.unit_normal(cell));
        for (unsigned int v = 0; v < 2; ++v)
        {
          auto &at_vertex = fixed_at_vertex[face->vertex_index(v)];
          append(at_vertex.translations, fixed.translations);
          append(at_vertex.rotations, fixed.rotations);
        }
      }
    for (const auto &[point, condition] : point_conditions_)
    {
      const FixedDirections fixed =
          directions_of(condition, Tensor<1, 3>(), Tensor<1, 3>());
      auto &at_vertex = fixed_at_vertex[model.nearest_vertex(point)];
      append(at_vertex.translations, fixed.translations);
      append(at_vertex.rotations, fixed.rotations);
    }
    for (const auto &[id, condition] : conditions_)
      if (ids_in_mesh.count(id) == 0)
      {
        std::ostringstream ids;
        for (const auto present : ids_in_mesh)
          ids << ' ' << present;
        throw std::invalid_argument(
            "Boundary conditions/Conditions names boundary id " +
            std::to_string(id) +
            ", which the mesh does not have (its "
            "boundary ids:" +
            ids.str() + ")");
      }
    for (const auto &[vertex, fixed] : fixed_at_vertex)
    {
      const VertexDofs &dofs = model.vertex_dofs(vertex);
      constrain_block(fixed.translations, {{dofs[ux], dofs[uy], dofs[uz]}},
                      constraints);
      constrain_block(fixed.rotations, {{dofs[rx], dofs[ry], dofs[rz]}},
                      constraints);
    }
  }
} // namespace coshell::model
