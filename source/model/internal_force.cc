#include <coshell/model/internal_force.h>

namespace coshell::model
{
  using namespace dealii;

  element::SpatialTriangle current_triangle(const ShellModel   &model,
                                            const CellIterator &cell,
                                            const ShellState   &state)
  {
    element::SpatialTriangle current = model.triangle(cell);
    for (unsigned int v = 0; v < 3; ++v)
      for (unsigned int d = 0; d < 3; ++d)
        current[v][d] += state.values()[cell->vertex_dof_index(v, ux + d)];
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

  element::NodalRotations
  InternalForce::nodal_rotations(const CellIterator &cell,
                                 const ShellState   &state) const
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

  double InternalForce::cell_energy(const CellIterator &cell,
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
      energy += cell_energy(cell, state);
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
    /// Largest principal value in magnitude of the symmetric 2 x 2 tensor
    /// (xx, yy, xy).
    double largest_principal(double xx, double yy, double xy)
    {
      const double centre = 0.5 * (xx + yy);
      const double radius = std::hypot(0.5 * (xx - yy), xy);
      return std::abs(centre) + radius;
    }
  } // namespace

  /// Plane stress: eps = (N_xx - nu N_yy, N_yy - nu N_xx, (1 + nu) N_xy)
  /// / (E h) (tensor shear component), and the curvature likewise from
  /// M with 12 / (E h^3); the surface strain is h/2 times the curvature.
  LargestStrains
  largest_strains(const ShellModel                            &model,
                  const std::vector<element::ShellResultants> &resultants)
  {
    LargestStrains largest;
    for (const auto &cell : model.dof_handler().active_cell_iterators())
    {
      const auto  &m  = model.material(cell);
      const auto  &r  = resultants[cell->active_cell_index()];
      const double nu = m.poisson_ratio, h = m.thickness;
      const auto  &n = r.membrane_local;
      const auto  &b = r.bending_local;
      const double membrane =
          largest_principal(n[0] - nu * n[1], n[1] - nu * n[0],
                            (1 + nu) * n[2]) /
          (m.youngs_modulus * h);
      const double bending =
          largest_principal(b[0] - nu * b[1], b[1] - nu * b[0],
                            (1 + nu) * b[2]) *
          6 / (m.youngs_modulus * h * h);
      largest.membrane = std::max(largest.membrane, membrane);
      largest.bending  = std::max(largest.bending, bending);
    }
    return largest;
  }
} // namespace coshell::model
