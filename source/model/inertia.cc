#include <coshell/element/shell_element.h>
#include <coshell/io/expressions.h>
#include <coshell/model/inertia.h>
#include <coshell/model/internal_force.h>

#include <deal.II/base/function_parser.h>
#include <deal.II/base/utilities.h>

#include <memory>
#include <stdexcept>

namespace coshell::model
{
  using namespace dealii;

  namespace
  {
    /// Three muparser expressions of x, y, z.
    std::unique_ptr<FunctionParser<3>> vector_field(const std::string &text,
                                                    const std::string &where)
    {
      return io::parse_expressions<3>(text, 3, "x,y,z", false, "x, y, z",
                                      where);
    }

    void require_non_negative(double value, const std::string &name)
    {
      if (!(value >= 0))
        throw std::invalid_argument("Mass and damping/" + name + " = " +
                                    std::to_string(value) +
                                    " must not be negative");
    }
  } // namespace

  void InertiaParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Mass and damping");
    prm.declare_entry("Mass matrix", "consistent",
                      Patterns::Selection("consistent|lumped"),
                      "Translational mass rho h A: consistent (linear "
                      "interpolation of the velocity) or lumped (a third per "
                      "vertex). Used in dynamics only (Material/Density "
                      "gives rho).");
    prm.declare_entry("Rotary inertia factor", "1", Patterns::Double(0),
                      "Dimensionless factor on the nodal rotary inertia "
                      "rho h^3/12 * A/3 (lumped, the same about every axis). "
                      "Larger values raise the highest (drilling and "
                      "bending) frequencies' periods, allowing larger "
                      "explicit-like steps, at the cost of accuracy in "
                      "fast rotations; must be > 0.");
    prm.declare_entry("Rayleigh mass coefficient", "0", Patterns::Double(0),
                      "alpha of the damping C = alpha M + beta K, in 1/s.");
    prm.declare_entry("Rayleigh stiffness coefficient", "0",
                      Patterns::Double(0),
                      "beta of the damping C = alpha M + beta K, in s (K: the "
                      "linear stiffness of the current triangles, which "
                      "does not damp rigid motions).");
    prm.declare_entry("Normal drag", "0", Patterns::Double(0),
                      "Viscous drag of the surrounding medium against the "
                      "normal velocity, force per area per velocity (e.g. "
                      "N s/m^3, or N s/mm^3 in mm-N-s scenes).");
    prm.declare_entry("Tangential drag", "0", Patterns::Double(0),
                      "Viscous drag against the in-plane velocity, force "
                      "per area per velocity.");
    prm.declare_entry("Initial velocity", "0; 0; 0", Patterns::Anything(),
                      "Velocity at the start of the scene, three muparser "
                      "expressions of the position x, y, z separated by "
                      "';', in length/s.");
    prm.declare_entry("Initial angular velocity", "0; 0; 0",
                      Patterns::Anything(),
                      "Angular velocity of the nodal triads at the start, "
                      "three expressions of x, y, z, in rad/s.");
    prm.leave_subsection();
  }

  void InertiaParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Mass and damping");
    mass_matrix              = prm.get("Mass matrix") == "lumped"
                                   ? element::MassMatrix::lumped
                                   : element::MassMatrix::consistent;
    rotary_inertia_factor    = prm.get_double("Rotary inertia factor");
    rayleigh_alpha           = prm.get_double("Rayleigh mass coefficient");
    rayleigh_beta            = prm.get_double("Rayleigh stiffness coefficient");
    normal_drag              = prm.get_double("Normal drag");
    tangential_drag          = prm.get_double("Tangential drag");
    initial_velocity         = prm.get("Initial velocity");
    initial_angular_velocity = prm.get("Initial angular velocity");
    prm.leave_subsection();
    if (rotary_inertia_factor <= 0)
      throw std::invalid_argument("Mass and damping/Rotary inertia factor = " +
                                  std::to_string(rotary_inertia_factor) +
                                  " must be positive (the rotations need "
                                  "mass)");
    require_non_negative(rayleigh_alpha, "Rayleigh mass coefficient");
    require_non_negative(rayleigh_beta, "Rayleigh stiffness coefficient");
    vector_field(initial_velocity, "Mass and damping/Initial velocity");
    vector_field(initial_angular_velocity,
                 "Mass and damping/Initial angular velocity");
  }

  bool InertiaParameters::damped() const
  {
    return rayleigh_alpha > 0 || rayleigh_beta > 0 || normal_drag > 0 ||
           tangential_drag > 0;
  }

  Inertia::Inertia(const ShellModel &model, const InertiaParameters &parameters)
      : model_(model), parameters_(parameters)
  {
  }

  element::MassProperties
  Inertia::mass_properties(const CellIterator &cell) const
  {
    const auto &material = model_.material(cell);
    return {material.density, material.thickness,
            parameters_.rotary_inertia_factor, parameters_.mass_matrix};
  }

  std::string Inertia::name() const
  {
    return "inertia and damping";
  }

  ForceKind Inertia::kind() const
  {
    return ForceKind::inertia;
  }

  bool Inertia::has_cell_terms() const
  {
    return true;
  }

  bool Inertia::symmetric_tangent() const
  {
    return true;
  }

  std::array<double, element::shell_dofs>
  Inertia::spatial_rates(const CellIterator   &cell,
                         const ShellState     &state,
                         const Vector<double> &rates) const
  {
    std::array<double, element::shell_dofs> spatial;
    for (unsigned int v = 0; v < 3; ++v)
    {
      Tensor<1, 3> translation, rotation;
      for (unsigned int d = 0; d < 3; ++d)
      {
        translation[d] = rates[cell->vertex_dof_index(v, ux + d)];
        rotation[d]    = rates[cell->vertex_dof_index(v, rx + d)];
      }
      if (state.finite_rotations())
        rotation = state.rotation(cell->vertex_index(v)) * rotation;
      for (unsigned int d = 0; d < 3; ++d)
      {
        spatial[6 * v + d]     = translation[d];
        spatial[6 * v + 3 + d] = rotation[d];
      }
    }
    return spatial;
  }

  FullMatrix<double> Inertia::damping(const CellIterator             &cell,
                                      const element::SpatialTriangle &current,
                                      const FullMatrix<double> &mass) const
  {
    FullMatrix<double> c(element::shell_dofs, element::shell_dofs);
    if (parameters_.rayleigh_alpha > 0)
      c.add(parameters_.rayleigh_alpha, mass);
    if (parameters_.rayleigh_beta > 0)
    {
      c.add(parameters_.rayleigh_beta,
            element::shell_stiffness(current, model_.material(cell),
                                     model_.element_parameters().options));
    }
    if (parameters_.normal_drag > 0 || parameters_.tangential_drag > 0)
    {
      const FullMatrix<double> drag = element::drag_matrix(
          current, parameters_.normal_drag, parameters_.tangential_drag);
      for (unsigned int a = 0; a < 9; ++a)
        for (unsigned int b = 0; b < 9; ++b)
          c(6 * (a / 3) + a % 3, 6 * (b / 3) + b % 3) += drag(a, b);
    }
    return c;
  }

  void Inertia::add_cell(const CellIterator    &cell,
                         const EvaluationPoint &point,
                         CellContribution      &contribution,
                         bool                   with_tangent) const
  {
    const ShellState        &state = point.state;
    const FullMatrix<double> mass =
        element::shell_mass(model_.triangle(cell), mass_properties(cell));
    const auto acceleration = spatial_rates(cell, state, state.acceleration());
    for (unsigned int i = 0; i < element::shell_dofs; ++i)
      for (unsigned int j = 0; j < element::shell_dofs; ++j)
        contribution.vector[i] -= mass(i, j) * acceleration[j];
    if (with_tangent)
      contribution.matrix.add(point.acceleration_coefficient, mass);
    if (!parameters_.damped())
      return;
    const FullMatrix<double> c =
        damping(cell, current_triangle(model_, cell, state), mass);
    const auto velocity = spatial_rates(cell, state, state.velocity());
    for (unsigned int i = 0; i < element::shell_dofs; ++i)
      for (unsigned int j = 0; j < element::shell_dofs; ++j)
        contribution.vector[i] -= c(i, j) * velocity[j];
    if (with_tangent)
      contribution.matrix.add(point.velocity_coefficient, c);
  }

  KineticMeasures Inertia::measures(const ShellState &state,
                                    Vector<double>   *damping_force) const
  {
    KineticMeasures result;
    if (damping_force)
      *damping_force = 0;
    for (const auto &cell : model_.dof_handler().active_cell_iterators())
    {
      const FullMatrix<double> mass =
          element::shell_mass(model_.triangle(cell), mass_properties(cell));
      const auto velocity = spatial_rates(cell, state, state.velocity());
      const auto current  = current_triangle(model_, cell, state);
      std::array<double, element::shell_dofs> momentum{};
      for (unsigned int i = 0; i < element::shell_dofs; ++i)
        for (unsigned int j = 0; j < element::shell_dofs; ++j)
          momentum[i] += mass(i, j) * velocity[j];
      for (unsigned int v = 0; v < 3; ++v)
      {
        Tensor<1, 3> p, spin_momentum;
        for (unsigned int d = 0; d < 3; ++d)
        {
          p[d]             = momentum[6 * v + d];
          spin_momentum[d] = momentum[6 * v + 3 + d];
        }
        result.linear_momentum += p;
        result.angular_momentum +=
            cross_product_3d(current[v], p) + spin_momentum;
      }
      for (unsigned int i = 0; i < element::shell_dofs; ++i)
        result.kinetic_energy += 0.5 * velocity[i] * momentum[i];
      if (parameters_.damped() && damping_force)
      {
        const FullMatrix<double> c = damping(cell, current, mass);
        for (unsigned int i = 0; i < element::shell_dofs; ++i)
          for (unsigned int j = 0; j < element::shell_dofs; ++j)
            (*damping_force)[cell->vertex_dof_index(i / 6, i % 6)] +=
                c(i, j) * velocity[j];
      }
    }
    return result;
  }

  void Inertia::set_initial_velocity(ShellState &state) const
  {
    const auto velocity = vector_field(parameters_.initial_velocity, "");
    const auto spin = vector_field(parameters_.initial_angular_velocity, "");
    Vector<double> value(3);
    const auto    &vertices = model_.surface().get_vertices();
    for (unsigned int v = 0; v < vertices.size(); ++v)
      if (model_.vertex_is_used(v))
      {
        const VertexDofs  &dofs = model_.vertex_dofs(v);
        const Tensor<2, 3> R    = state.rotation(v);
        velocity->vector_value(vertices[v], value);
        for (unsigned int d = 0; d < 3; ++d)
          state.velocity()[dofs[ux + d]] = value[d];
        spin->vector_value(vertices[v], value);
        // Material angular velocity Omega = R^T omega.
        const Tensor<1, 3> omega({value[0], value[1], value[2]});
        const Tensor<1, 3> material =
            state.finite_rotations() ? transpose(R) * omega : omega;
        for (unsigned int d = 0; d < 3; ++d)
          state.velocity()[dofs[rx + d]] = material[d];
      }
  }
} // namespace coshell::model
