#include <coshell/model/internal_force.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace coshell::model
{
  using namespace dealii;

  element::SpatialTriangle current_triangle(const ShellModel   &model,
                                            const CellIterator &cell,
                                            const ShellState   &state)
  {
    element::SpatialTriangle current = model.triangle(cell);
    for (unsigned int v = 0; v < 3; ++v)
      current[v] += vertex_block(state.values(),
                                 model.vertex_dofs(cell->vertex_index(v)), ux);
    return current;
  }

  InternalForce::InternalForce(const ShellModel            &model,
                               Formulation                  kinematics,
                               element::CorotationalTangent tangent,
                               bool                         extrapolated_forces,
                               bool                         exact_after_failure)
      : model_(model), kinematics_(kinematics), tangent_(tangent),
        extrapolate_(extrapolated_forces &&
                     kinematics == Formulation::corotational &&
                     tangent != element::CorotationalTangent::paper),
        exact_after_failure_(exact_after_failure)
  {
    if (kinematics_ != Formulation::corotational)
      return;
    corotational_.reserve(model.surface().n_active_cells());
    for (const auto &cell : model.dof_handler().active_cell_iterators())
      corotational_.emplace_back(model.triangle(cell), model.material(cell),
                                 model.element_options(cell));
    if (extrapolate_)
      history_.resize(corotational_.size());
  }

  void InternalForce::begin_solve()
  {
    forget_history();
  }

  void InternalForce::restore()
  {
    forget_history();
    a_step_failed_ = true;
  }

  void InternalForce::forget_history()
  {
    for (auto &h : history_)
      h.valid = false;
  }

  std::string InternalForce::name() const
  {
    return "internal force";
  }

  ForceKind InternalForce::kind() const
  {
    return ForceKind::internal;
  }

  bool InternalForce::has_cell_terms() const
  {
    return true;
  }

  bool InternalForce::symmetric_tangent() const
  {
    return kinematics_ == Formulation::linear ||
           tangent_ != element::CorotationalTangent::consistent;
  }

  element::NodalRotations nodal_rotations(const CellIterator &cell,
                                          const ShellState   &state)
  {
    return {{state.rotation(cell->vertex_index(0)),
             state.rotation(cell->vertex_index(1)),
             state.rotation(cell->vertex_index(2))}};
  }

  void InternalForce::add_cell(const CellIterator    &cell,
                               const EvaluationPoint &point,
                               CellContribution      &contribution,
                               bool                   with_tangent) const
  {
    if (kinematics_ == Formulation::linear)
    {
      const FullMatrix<double> stiffness =
          element::shell_stiffness(model_.triangle(cell), model_.material(cell),
                                   model_.element_options(cell));
      const auto u = model_.cell_values(cell, point.state.values());
      for (unsigned int i = 0; i < element::shell_dofs; ++i)
        for (unsigned int j = 0; j < element::shell_dofs; ++j)
          contribution.vector[i] -= stiffness(i, j) * u[j];
      if (with_tangent)
        contribution.matrix.add(1.0, stiffness);
      return;
    }
    add_corotational_cell(cell, point, contribution, with_tangent);
  }

  namespace
  {
    bool same_configuration(const element::SpatialTriangle &x,
                            const element::NodalRotations  &r,
                            const element::SpatialTriangle &y,
                            const element::NodalRotations  &s)
    {
      for (unsigned int v = 0; v < 3; ++v)
        if (x[v] != y[v] || r[v] != s[v])
          return false;
      return true;
    }

    /// d + J dp, dp the perturbation (translations, spatial rotation
    /// vectors R_new R_old^T) from the old configuration to the new one.
    element::ShellDisplacements
    extrapolate(const element::CorotationalLinearization &old_linearization,
                const element::SpatialTriangle           &old_triangle,
                const element::NodalRotations            &old_rotations,
                const element::SpatialTriangle           &triangle,
                const element::NodalRotations            &rotations)
    {
      element::ShellDisplacements dp;
      for (unsigned int v = 0; v < 3; ++v)
      {
        const Tensor<1, 3> spin =
            element::rotation_log(rotations[v] * transpose(old_rotations[v]));
        for (unsigned int c = 0; c < 3; ++c)
        {
          dp[6 * v + c]     = triangle[v][c] - old_triangle[v][c];
          dp[6 * v + 3 + c] = spin[c];
        }
      }
      element::ShellDisplacements d = old_linearization.dofs;
      for (unsigned int a = 0; a < element::shell_dofs; ++a)
        for (unsigned int b = 0; b < element::shell_dofs; ++b)
          d[a] += old_linearization.jacobian[a][b] * dp[b];
      return d;
    }
  } // namespace

  void InternalForce::add_corotational_cell(const CellIterator    &cell,
                                            const EvaluationPoint &point,
                                            CellContribution      &contribution,
                                            bool with_tangent) const
  {
    const unsigned int index     = cell->active_cell_index();
    const auto         triangle  = current_triangle(model_, cell, point.state);
    const auto         rotations = nodal_rotations(cell, point.state);
    element::ShellDisplacements force;
    // Reused: an 18 x 18 allocation per cell and evaluation showed.
    thread_local FullMatrix<double> tangent;
    if (!with_tangent || !extrapolate_ ||
        (exact_after_failure_ && a_step_failed_))
      corotational_[index].internal_force(triangle, rotations, tangent_, force,
                                          with_tangent ? &tangent : nullptr);
    else
    {
      TangentHistory             &h = history_[index];
      element::ShellDisplacements geometric;
      const bool same = h.valid && same_configuration(h.triangle, h.rotations,
                                                      triangle, rotations);
      if (same)
        geometric = h.geometric_dofs;
      else if (h.valid)
        geometric = extrapolate(h.linearization, h.triangle, h.rotations,
                                triangle, rotations);
      // A new configuration's linearization replaces the old one, which
      // the extrapolation above has used.
      corotational_[index].internal_force(
          triangle, rotations, tangent_, force, &tangent,
          h.valid ? &geometric : nullptr, same ? nullptr : &h.linearization);
      if (!same)
      {
        h.geometric_dofs = h.valid ? geometric : h.linearization.dofs;
        h.valid          = true;
        h.triangle       = triangle;
        h.rotations      = rotations;
      }
    }
    for (unsigned int i = 0; i < element::shell_dofs; ++i)
      contribution.vector[i] -= force[i];
    if (with_tangent)
      contribution.matrix.add(1.0, tangent);
  }

  bool InternalForce::has_potential() const
  {
    return true;
  }

  double InternalForce::cell_energy(const CellIterator    &cell,
                                    const EvaluationPoint &point) const
  {
    return strain_energy(cell, point.state);
  }

  double InternalForce::strain_energy(const CellIterator &cell,
                                      const ShellState   &state) const
  {
    if (kinematics_ == Formulation::corotational)
      return corotational_[cell->active_cell_index()].energy(
          current_triangle(model_, cell, state), nodal_rotations(cell, state));
    const FullMatrix<double> stiffness =
        element::shell_stiffness(model_.triangle(cell), model_.material(cell),
                                 model_.element_options(cell));
    const auto u      = model_.cell_values(cell, state.values());
    double     energy = 0;
    for (unsigned int i = 0; i < element::shell_dofs; ++i)
      for (unsigned int j = 0; j < element::shell_dofs; ++j)
        energy += 0.5 * u[i] * stiffness(i, j) * u[j];
    return energy;
  }

  double InternalForce::strain_energy(const ShellState &state) const
  {
    double energy = 0;
    for (const auto &cell : model_.dof_handler().active_cell_iterators())
      energy += strain_energy(cell, state);
    return energy;
  }

  std::vector<element::ShellResultants>
  InternalForce::resultants(const ShellState &state) const
  {
    if (kinematics_ == Formulation::linear)
      return model_.resultants(state.values());
    std::vector<element::ShellResultants> result(corotational_.size());
    for (const auto &cell : model_.dof_handler().active_cell_iterators())
    {
      auto &r = result[cell->active_cell_index()];
      r       = corotational_[cell->active_cell_index()].resultants(
                current_triangle(model_, cell, state), nodal_rotations(cell, state));
      model_.orient_moments(cell, r);
    }
    return result;
  }

  namespace
  {
    /// A symmetric 2 x 2 tensor (xx, yy, xy).
    using PlaneTensor = std::array<double, 3>;

    /// Largest principal value in magnitude.
    double largest_principal(const PlaneTensor &s)
    {
      const double centre = 0.5 * (s[0] + s[1]);
      const double radius = std::hypot(0.5 * (s[0] - s[1]), s[2]);
      return std::abs(centre) + radius;
    }

    /// Plane stress inverted: the strain tensor (tensor shear component)
    /// of a resultant r, eps = (r_xx - nu r_yy, r_yy - nu r_xx,
    /// (1 + nu) r_xy) times 'compliance'.
    PlaneTensor
    plane_strain_of(const PlaneTensor &r, double nu, double compliance)
    {
      return {compliance * (r[0] - nu * r[1]), compliance * (r[1] - nu * r[0]),
              compliance * (1 + nu) * r[2]};
    }
  } // namespace

  /// Membrane strain N / (E h); bending strain at the surfaces 6 M / (E h^2),
  /// h/2 times the curvature 12 M / (E h^3).
  CellStrains cell_strains(const element::ShellMaterial   &material,
                           const element::ShellResultants &resultants)
  {
    const double nu = material.poisson_ratio, E = material.youngs_modulus,
                 h = material.thickness;
    const PlaneTensor middle =
        plane_strain_of(resultants.membrane_local, nu, 1 / (E * h));
    const PlaneTensor bending =
        plane_strain_of(resultants.bending_local, nu, 6 / (E * h * h));
    CellStrains strains;
    strains.membrane = largest_principal(middle);
    strains.bending  = largest_principal(bending);
    for (const double side : {-1.0, 1.0})
      strains.surface = std::max(
          strains.surface, largest_principal({middle[0] + side * bending[0],
                                              middle[1] + side * bending[1],
                                              middle[2] + side * bending[2]}));
    return strains;
  }

  LargestStrains
  largest_strains(const ShellModel                            &model,
                  const std::vector<element::ShellResultants> &resultants)
  {
    LargestStrains largest;
    for (const auto &cell : model.dof_handler().active_cell_iterators())
    {
      const CellStrains strains = cell_strains(
          model.material(cell), resultants[cell->active_cell_index()]);
      largest.membrane = std::max(largest.membrane, strains.membrane);
      largest.bending  = std::max(largest.bending, strains.bending);
      largest.surface  = std::max(largest.surface, strains.surface);
    }
    return largest;
  }
} // namespace coshell::model
