#include <coshell/model/internal_force.h>
#include <coshell/model/thickness_stretch.h>

#include <algorithm>

namespace coshell::model
{
  using namespace dealii;

  namespace
  {
    // Index in a cell's block of position component d of vertex v (the
    // kernel order 6 v + d) and of vertex v's stretch.
    constexpr unsigned int position_index(unsigned int v, unsigned int d)
    {
      return dofs_per_vertex * v + d;
    }
    constexpr unsigned int stretch_index(unsigned int v)
    {
      return element::shell_dofs + v;
    }
    constexpr unsigned int block_size = element::shell_dofs + 3;

    // s = sum lambda^3 / 3 and its derivatives in each lambda.
    struct BendingScale
    {
      double                value = 0;
      std::array<double, 3> slope{}, curvature{};
    };

    BendingScale bending_scale(const std::array<double, 3> &lambda)
    {
      BendingScale scale;
      for (unsigned int v = 0; v < 3; ++v)
      {
        scale.value += lambda[v] * lambda[v] * lambda[v] / 3;
        scale.slope[v]     = lambda[v] * lambda[v];
        scale.curvature[v] = 2 * lambda[v];
      }
      return scale;
    }
  } // namespace

  ThickMembraneForce::ThickMembraneForce(const ShellModel &model)
      : model_(model)
  {
    membranes_.reserve(model.surface().n_active_cells());
    for (const auto &cell : model.dof_handler().active_cell_iterators())
    {
      const auto &material = model.material(cell);
      membranes_.emplace_back(
          element::make_element_frame(model.triangle(cell)).planar,
          material.thickness, element::NeoHookeanLaw::from_material(material));
      element::ShellElementOptions bending_only = model.element_options(cell);
      bending_only.membrane                     = std::nullopt;
      if (bending_only.bending)
        bending_.emplace_back(model.triangle(cell), material, bending_only);
    }
  }

  std::string ThickMembraneForce::name() const
  {
    return "thick membrane";
  }

  ForceKind ThickMembraneForce::kind() const
  {
    return ForceKind::internal;
  }

  bool ThickMembraneForce::has_cell_terms() const
  {
    return false;
  }

  bool ThickMembraneForce::symmetric_tangent() const
  {
    return true;
  }

  bool ThickMembraneForce::has_potential() const
  {
    return true;
  }

  std::array<double, 3>
  ThickMembraneForce::stretches(const CellIterator &cell,
                                const ShellState   &state) const
  {
    std::array<double, 3> lambda;
    for (unsigned int v = 0; v < 3; ++v)
      lambda[v] =
          model_.thickness_stretch(cell->vertex_index(v), state.values());
    return lambda;
  }

  void ThickMembraneForce::cell_dofs(
      const CellIterator                   &cell,
      std::vector<types::global_dof_index> &dofs) const
  {
    dofs.resize(element::shell_dofs);
    cell->get_dof_indices(dofs);
    for (unsigned int v = 0; v < 3; ++v)
      dofs.push_back(model_.thickness_dof(cell->vertex_index(v)));
  }

  ThickMembraneForce::CellConfiguration
  ThickMembraneForce::configuration(const CellIterator &cell,
                                    const ShellState   &state) const
  {
    return {current_triangle(model_, cell, state), stretches(cell, state)};
  }

  void ThickMembraneForce::add_membrane(const CellIterator      &cell,
                                        const CellConfiguration &at,
                                        DofBlock                &block,
                                        bool with_tangent) const
  {
    Vector<double>     gradient;
    FullMatrix<double> hessian;
    membranes_[cell->active_cell_index()].derivatives(
        at.positions, at.stretches, gradient, hessian);
    // The kernel's 9 positions (3 v + d) and 3 stretches (9 + v).
    std::array<unsigned int, element::thick_membrane_dofs> to_block;
    for (unsigned int v = 0; v < 3; ++v)
    {
      for (unsigned int d = 0; d < 3; ++d)
        to_block[3 * v + d] = position_index(v, d);
      to_block[9 + v] = stretch_index(v);
    }
    // r = f_ext - f_int: the residual takes minus the energy's gradient,
    // the tangent -dr/du its Hessian.
    for (unsigned int i = 0; i < element::thick_membrane_dofs; ++i)
    {
      block.vector[to_block[i]] -= gradient[i];
      if (with_tangent)
        for (unsigned int j = 0; j < element::thick_membrane_dofs; ++j)
          block.matrix(to_block[i], to_block[j]) += hessian(i, j);
    }
  }

  void ThickMembraneForce::add_bending_change(const CellIterator      &cell,
                                              const ShellState        &state,
                                              const CellConfiguration &at,
                                              DofBlock                &block,
                                              bool with_tangent) const
  {
    if (bending_.empty())
      return;
    const auto                 &bending  = bending_[cell->active_cell_index()];
    const auto                 &current  = at.positions;
    const auto                  rotation = nodal_rotations(cell, state);
    const auto                  scale    = bending_scale(at.stretches);
    element::ShellDisplacements force;
    FullMatrix<double>          tangent;
    bending.internal_force(current, rotation,
                           element::CorotationalTangent::symmetric, force,
                           with_tangent ? &tangent : nullptr);
    const double energy = bending.energy(current, rotation);
    for (unsigned int i = 0; i < element::shell_dofs; ++i)
      block.vector[i] -= (scale.value - 1) * force[i];
    for (unsigned int v = 0; v < 3; ++v)
      block.vector[stretch_index(v)] -= scale.slope[v] * energy;
    if (!with_tangent)
      return;
    for (unsigned int i = 0; i < element::shell_dofs; ++i)
    {
      for (unsigned int j = 0; j < element::shell_dofs; ++j)
        block.matrix(i, j) += (scale.value - 1) * tangent(i, j);
      for (unsigned int v = 0; v < 3; ++v)
      {
        block.matrix(i, stretch_index(v)) += scale.slope[v] * force[i];
        block.matrix(stretch_index(v), i) += scale.slope[v] * force[i];
      }
    }
    for (unsigned int v = 0; v < 3; ++v)
      block.matrix(stretch_index(v), stretch_index(v)) +=
          scale.curvature[v] * energy;
  }

  void ThickMembraneForce::add_blocks(const EvaluationPoint &point,
                                      const BlockSink       &sink,
                                      bool                   with_tangent)
  {
    DofBlock block;
    for (const auto &cell : model_.dof_handler().active_cell_iterators())
    {
      cell_dofs(cell, block.dofs);
      block.vector.reinit(block_size);
      block.matrix.reinit(with_tangent ? block_size : 0,
                          with_tangent ? block_size : 0);
      const CellConfiguration at = configuration(cell, point.state);
      add_membrane(cell, at, block, with_tangent);
      add_bending_change(cell, point.state, at, block, with_tangent);
      sink(block);
    }
  }

  double ThickMembraneForce::global_energy(const EvaluationPoint &point) const
  {
    return energy(point.state);
  }

  double ThickMembraneForce::admissible_fraction(
      const ShellState &state, const Vector<double> &correction) const
  {
    constexpr double kept     = 0.2;
    double           fraction = 1;
    for (auto i = model_.n_fe_dofs(); i < model_.n_dofs(); ++i)
      if (correction[i] < 0)
        fraction = std::min(fraction, (1 - kept) * (1 + state.values()[i]) /
                                          -correction[i]);
    return fraction;
  }

  double stored_energy(const ShellProblem &problem, const ShellState &state)
  {
    double energy = problem.find<InternalForce>()->strain_energy(state);
    if (const auto *thick = problem.find<ThickMembraneForce>())
      energy += thick->energy(state);
    return energy;
  }

  double ThickMembraneForce::energy(const ShellState &state) const
  {
    double energy = 0;
    for (const auto &cell : model_.dof_handler().active_cell_iterators())
    {
      const CellConfiguration at = configuration(cell, state);
      energy += membranes_[cell->active_cell_index()].energy(at.positions,
                                                             at.stretches);
      if (!bending_.empty())
        energy += (bending_scale(at.stretches).value - 1) *
                  bending_[cell->active_cell_index()].energy(
                      at.positions, nodal_rotations(cell, state));
    }
    return energy;
  }

  FacePressure::FacePressure(const ShellModel &model, double pressure)
      : model_(model), load_(model.n_dofs())
  {
    for (const auto &cell : model.dof_handler().active_cell_iterators())
    {
      const double weight = pressure * element::area(model.triangle(cell)) *
                            model.material(cell).thickness / 3.0;
      for (unsigned int v = 0; v < 3; ++v)
        load_[model.thickness_dof(cell->vertex_index(v))] -= weight;
    }
  }

  std::string FacePressure::name() const
  {
    return "face pressure";
  }

  ForceKind FacePressure::kind() const
  {
    return ForceKind::external;
  }

  bool FacePressure::has_cell_terms() const
  {
    return false;
  }

  bool FacePressure::symmetric_tangent() const
  {
    return true;
  }

  bool FacePressure::has_potential() const
  {
    return true;
  }

  void FacePressure::add_global(const EvaluationPoint &point,
                                Vector<double>        &residual) const
  {
    residual.add(point.load_factor, load_);
  }

  double FacePressure::global_energy(const EvaluationPoint &point) const
  {
    return -point.load_factor * (load_ * point.state.values());
  }
} // namespace coshell::model
