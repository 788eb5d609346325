#include <coshell/element/corotational.h>
#include <coshell/model/external_loads.h>
#include <coshell/model/internal_force.h>

namespace coshell::model
{
  using namespace dealii;

  ExternalLoads::ExternalLoads(const ShellModel &model,
                               const Loads      &loads,
                               bool              finite_rotations,
                               std::ostream     &log)
      : model_(model), dead_load_(model.n_dofs()),
        follower_pressure_(finite_rotations ? loads.follower_pressure() : 0)
  {
    loads.assemble(model, dead_load_, log, finite_rotations);
    if (finite_rotations)
      for (unsigned int v = 0; v < model.surface().n_vertices(); ++v)
        if (model.vertex_is_used(v))
          for (unsigned int d = 0; d < 3; ++d)
            moments_on_finite_rotations_ =
                moments_on_finite_rotations_ ||
                dead_load_[model.vertex_dofs(v)[rx + d]] != 0;
  }

  std::string ExternalLoads::name() const
  {
    return "external loads";
  }

  ForceKind ExternalLoads::kind() const
  {
    return ForceKind::external;
  }

  bool ExternalLoads::has_cell_terms() const
  {
    return follower_pressure_ != 0;
  }

  bool ExternalLoads::symmetric_tangent() const
  {
    return follower_pressure_ == 0;
  }

  void ExternalLoads::add_cell(const CellIterator    &cell,
                               const EvaluationPoint &point,
                               CellContribution      &contribution,
                               bool                   with_tangent) const
  {
    const double pressure =
        point.load_factor * follower_pressure_ * model_.normal_sign(cell);
    if (pressure == 0)
      return;
    std::array<double, 9> force;
    FullMatrix<double>    stiffness(9, 9);
    element::follower_pressure(current_triangle(model_, cell, point.state),
                               pressure, force,
                               with_tangent ? &stiffness : nullptr);
    // Translations only: node a, direction i -> element DoF 6a + i.
    for (unsigned int a = 0; a < 9; ++a)
    {
      const unsigned int row = 6 * (a / 3) + a % 3;
      contribution.vector[row] += force[a];
      if (with_tangent)
        for (unsigned int b = 0; b < 9; ++b)
          contribution.matrix(row, 6 * (b / 3) + b % 3) -= stiffness(a, b);
    }
  }

  bool ExternalLoads::has_potential() const
  {
    return follower_pressure_ == 0 && !moments_on_finite_rotations_;
  }

  double ExternalLoads::global_energy(const EvaluationPoint &point) const
  {
    // With finite rotations the rotation entries of the load are zero
    // (has_potential()), so the product holds the translations' work.
    return -point.load_factor * (dead_load_ * point.state.values());
  }

  void ExternalLoads::add_global(const EvaluationPoint &point,
                                 Vector<double>        &residual) const
  {
    residual.add(point.load_factor, dead_load_);
  }
} // namespace coshell::model
