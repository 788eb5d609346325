#include <coshell/base/expressions.h>
#include <coshell/element/corotational.h>
#include <coshell/model/prescribed_motions.h>

#include <deal.II/base/utilities.h>

#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

namespace coshell::model
{
  using namespace dealii;

  namespace
  {
    std::string motion_section(unsigned int number)
    {
      return "Motion " + std::to_string(number);
    }

    void parse_where(const std::string &text,
                     PrescribedMotion  &motion,
                     const std::string &where)
    {
      std::istringstream in(text);
      std::string        kind;
      in >> kind;
      motion.where = Utilities::trim(text);
      if (kind == "boundary" && in >> motion.boundary_id &&
          motion.boundary_id >= 0)
        return;
      if (kind == "point" &&
          in >> motion.point[0] >> motion.point[1] >> motion.point[2])
        return;
      throw std::invalid_argument(where + ": '" + text +
                                  "' is not 'boundary N' or 'point x y z'");
    }

    void parse_components(const std::string &text,
                          PrescribedMotion  &motion,
                          const std::string &where)
    {
      unsigned int rotations = 0;
      for (const auto &name : Utilities::split_string_list(text, ' '))
      {
        if (name.empty())
          continue;
        const Component c = parse_component(name);
        if (c < 3)
          motion.translations[c] = true;
        else
          ++rotations;
      }
      if (rotations != 0 && rotations != 3)
        throw std::invalid_argument(
            where + ": a finite rotation is prescribed as a whole: list all "
                    "of rx ry rz or none");
      motion.rotation = rotations == 3;
    }

    /// The vertices a motion moves.
    std::vector<unsigned int> vertices_of(const PrescribedMotion &motion,
                                          const ShellModel       &model,
                                          unsigned int            number)
    {
      if (motion.boundary_id < 0)
        return {model.nearest_vertex(motion.point)};
      std::set<unsigned int> vertices;
      for (const auto &cell : model.dof_handler().active_cell_iterators())
        for (unsigned int f = 0; f < cell->n_faces(); ++f)
          if (cell->at_boundary(f) &&
              cell->face(f)->boundary_id() == unsigned(motion.boundary_id))
            for (unsigned int v = 0; v < 2; ++v)
              vertices.insert(cell->face(f)->vertex_index(v));
      if (vertices.empty())
        throw std::invalid_argument(
            "Prescribed motions/" + motion_section(number) +
            " moves boundary " + std::to_string(motion.boundary_id) +
            ", which the mesh does not have");
      return {vertices.begin(), vertices.end()};
    }
  } // namespace

  void PrescribedMotions::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Prescribed motions");
    for (unsigned int k = 1; k <= max_motions; ++k)
    {
      prm.enter_subsection(motion_section(k));
      prm.declare_entry(
          "Where", "", Patterns::Anything(),
          "The vertices moved: 'boundary N' (every vertex of "
          "boundary id N) or 'point x y z' (the vertex nearest "
          "that point); empty: this motion is not defined. "
          "Unit: length for x y z (m in SI, mm in the IOL scenes).");
      prm.declare_entry("Components", "ux uy uz rx ry rz", Patterns::Anything(),
                        "Prescribed components, space separated: any of ux "
                        "uy uz, and rx ry rz all together or none (the "
                        "nodal rotation is prescribed as a whole).");
      RigidMotion::declare_entries(prm);
      prm.leave_subsection();
    }
    prm.leave_subsection();
  }

  void PrescribedMotions::parse_parameters(ParameterHandler &prm)
  {
    motions_.assign(max_motions, PrescribedMotion());
    prm.enter_subsection("Prescribed motions");
    for (unsigned int k = 1; k <= max_motions; ++k)
    {
      prm.enter_subsection(motion_section(k));
      const std::string where  = "Prescribed motions/" + motion_section(k);
      PrescribedMotion &motion = motions_[k - 1];
      try
      {
        if (!Utilities::trim(prm.get("Where")).empty())
        {
          parse_where(prm.get("Where"), motion, where + "/Where");
          parse_components(prm.get("Components"), motion,
                           where + "/Components");
          motion.motion.parse_entries(prm, where);
        }
      }
      catch (...)
      {
        prm.leave_subsection();
        prm.leave_subsection();
        throw;
      }
      prm.leave_subsection();
    }
    prm.leave_subsection();
  }

  std::vector<unsigned int> PrescribedMotions::defined() const
  {
    std::vector<unsigned int> numbers;
    for (unsigned int k = 0; k < motions_.size(); ++k)
      if (!motions_[k].where.empty())
        numbers.push_back(k + 1);
    return numbers;
  }

  bool PrescribedMotions::empty() const
  {
    return defined().empty();
  }

  void PrescribedMotions::make_constraints(
      const ShellModel                &model,
      const std::vector<unsigned int> &active,
      AffineConstraints<double>       &constraints) const
  {
    for (const unsigned int number : active)
    {
      const PrescribedMotion &motion = motions_.at(number - 1);
      for (const unsigned int v : vertices_of(motion, model, number))
      {
        const VertexDofs &dofs = model.vertex_dofs(v);
        for (unsigned int d = 0; d < 3; ++d)
        {
          if (motion.translations[d])
            constraints.add_line(dofs[ux + d]);
          if (motion.rotation)
            constraints.add_line(dofs[rx + d]);
        }
      }
    }
  }

  PrescribedIncrementFunction
  PrescribedMotions::increments(const ShellModel                &model,
                                const std::vector<unsigned int> &active) const
  {
    std::vector<std::pair<PrescribedMotion, std::vector<unsigned int>>> moved;
    for (const unsigned int number : active)
      moved.emplace_back(motions_.at(number - 1),
                         vertices_of(motions_.at(number - 1), model, number));
    if (moved.empty())
      return {};
    return [moved, &model](double time, const ShellState &state,
                           PrescribedIncrements &increments)
    {
      const auto &values = state.values();
      for (const auto &[motion, vertices] : moved)
      {
        const Tensor<1, 3> d      = motion.motion.displacement(time);
        const Tensor<1, 3> theta  = motion.motion.rotation_vector(time);
        const bool         finite = state.finite_rotations();
        const Tensor<2, 3> R      = element::rotation_exp(theta);
        for (const unsigned int v : vertices)
        {
          const Tensor<1, 3> arm =
              model.surface().get_vertices()[v] - motion.motion.centre;
          const Tensor<1, 3> u =
              (finite ? R * arm - arm : cross_product_3d(theta, arm)) + d;
          const VertexDofs &dofs = model.vertex_dofs(v);
          for (unsigned int c = 0; c < 3; ++c)
            if (motion.translations[c])
              increments.emplace_back(dofs[ux + c],
                                      u[c] - values[dofs[ux + c]]);
          if (!motion.rotation)
            continue;
          const Tensor<1, 3> spin =
              finite ? element::rotation_log(R * transpose(state.rotation(v)))
                     : theta - vertex_block(values, dofs, rx);
          for (unsigned int c = 0; c < 3; ++c)
            increments.emplace_back(dofs[rx + c], spin[c]);
        }
      }
    };
  }
} // namespace coshell::model
