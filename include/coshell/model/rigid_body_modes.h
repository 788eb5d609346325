#pragma once

#include <coshell/model/shell_model.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/vector.h>

#include <array>

namespace coshell::model
{
  /// The six infinitesimal rigid-body motions of the mesh as DoF vectors:
  /// translations along x, y, z, then rotations about x, y, z through the
  /// vertex centroid (u = omega x (X - c), theta = omega), with the
  /// rotations scaled by 1/(mesh size) so all six have comparable norms.
  /// Also the near-null space an algebraic multigrid wants.
  std::array<dealii::Vector<double>, 6>
  rigid_body_modes(const ShellModel &model);

  /// How many independent rigid-body motions the constraints leave free
  /// (0 to 6).
  unsigned int
  n_free_rigid_motions(const ShellModel                        &model,
                       const dealii::AffineConstraints<double> &constraints);

  /// Throws std::runtime_error, naming the motion, when the constraints
  /// leave a rigid-body motion free (the stiffness would be singular).
  void check_supports(const ShellModel                        &model,
                      const dealii::AffineConstraints<double> &constraints);
} // namespace coshell::model
