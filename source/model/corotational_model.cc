#include <coshell/model/corotational_model.h>

namespace coshell::model
{
  using namespace dealii;

  CorotationalModel::CorotationalModel(const ShellModel &model) : model_(model)
  {
    const auto &parameters = model.element_parameters();
    elements_.reserve(model.surface().n_active_cells());
    for (const auto &cell : model.dof_handler().active_cell_iterators())
      elements_.emplace_back(model.triangle(cell), parameters.material,
                             parameters.options);
  }

  element::SpatialTriangle
  CorotationalModel::current_triangle(const CellIterator &cell,
                                      const ShellState   &state) const
  {
    element::SpatialTriangle current = model_.triangle(cell);
    for (unsigned int v = 0; v < 3; ++v)
      for (unsigned int d = 0; d < 3; ++d)
        current[v][d] += state.values()[cell->vertex_dof_index(v, ux + d)];
    return current;
  }

  element::NodalRotations
  CorotationalModel::nodal_rotations(const CellIterator &cell,
                                     const ShellState   &state) const
  {
    return {{state.rotation(cell->vertex_index(0)),
             state.rotation(cell->vertex_index(1)),
             state.rotation(cell->vertex_index(2))}};
  }

  void CorotationalModel::add_follower_pressure(const CellIterator &cell,
                                                const ShellState   &state,
                                                double              pressure,
                                                CellContribution &contribution,
                                                bool with_stiffness) const
  {
    const double oriented_pressure = pressure * model_.normal_sign(cell);
    std::array<double, 9> force;
    FullMatrix<double>    stiffness(9, 9);
    element::follower_pressure(current_triangle(cell, state), oriented_pressure,
                               force, with_stiffness ? &stiffness : nullptr);
    // Translations only: node a, direction i -> element DoF 6a + i.
    for (unsigned int a = 0; a < 9; ++a)
    {
      const unsigned int row = 6 * (a / 3) + a % 3;
      contribution.vector[row] += force[a];
      if (with_stiffness)
        for (unsigned int b = 0; b < 9; ++b)
          contribution.matrix(row, 6 * (b / 3) + b % 3) -= stiffness(a, b);
    }
  }

  void CorotationalModel::assemble(const ShellState     &state,
                                   double                load_factor,
                                   const Vector<double> &dead_load,
                                   double                follower_pressure,
                                   element::CorotationalTangent tangent_type,
                                   const AffineConstraints<double> &constraints,
                                   Vector<double>                  &residual,
                                   SparseMatrix<double> *tangent) const
  {
    residual = 0;
    if (tangent)
      *tangent = 0;
    const double pressure = load_factor * follower_pressure;
    for_each_cell(
        model_.dof_handler(),
        [&](const CellIterator &cell, CellContribution &contribution)
        {
          element::ShellDisplacements force;
          contribution.matrix.reinit(element::shell_dofs, element::shell_dofs);
          elements_[cell->active_cell_index()].internal_force(
              current_triangle(cell, state), nodal_rotations(cell, state),
              tangent_type, force, tangent ? &contribution.matrix : nullptr);
          contribution.vector.reinit(element::shell_dofs);
          for (unsigned int i = 0; i < element::shell_dofs; ++i)
            contribution.vector[i] = -force[i];
          if (pressure != 0)
            add_follower_pressure(cell, state, pressure, contribution,
                                  tangent != nullptr);
        },
        [&](const CellContribution &contribution)
        {
          if (tangent)
            constraints.distribute_local_to_global(
                contribution.matrix, contribution.vector, contribution.dofs,
                *tangent, residual);
          else
            constraints.distribute_local_to_global(contribution.vector,
                                                   contribution.dofs, residual);
        });
    Vector<double> scaled_dead_load(dead_load);
    scaled_dead_load *= load_factor;
    constraints.condense(scaled_dead_load);
    residual += scaled_dead_load;
  }

  void CorotationalModel::load_vector(const ShellState     &state,
                                      const Vector<double> &dead_load,
                                      double                follower_pressure,
                                      Vector<double>       &load) const
  {
    load = dead_load;
    if (follower_pressure == 0)
      return;
    for_each_cell(
        model_.dof_handler(),
        [&](const CellIterator &cell, CellContribution &contribution)
        {
          contribution.vector.reinit(element::shell_dofs);
          add_follower_pressure(cell, state, follower_pressure, contribution,
                                false);
        },
        [&](const CellContribution &contribution)
        {
          for (unsigned int i = 0; i < element::shell_dofs; ++i)
            load[contribution.dofs[i]] += contribution.vector[i];
        });
  }

  std::vector<element::ShellResultants>
  CorotationalModel::resultants(const ShellState &state) const
  {
    std::vector<element::ShellResultants> result(elements_.size());
    for (const auto &cell : model_.dof_handler().active_cell_iterators())
    {
      auto &r = result[cell->active_cell_index()];
      r       = elements_[cell->active_cell_index()].resultants(
                current_triangle(cell, state), nodal_rotations(cell, state));
      model_.orient_moments(cell, r);
    }
    return result;
  }
} // namespace coshell::model
