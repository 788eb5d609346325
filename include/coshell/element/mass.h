#pragma once

// Mass of the flat shell triangle: translational mass rho h A with linear
// interpolation of the velocity (consistent) or a third per vertex
// (lumped), and a rotary inertia rho h^3 / 12 per unit area, lumped, the
// same about every axis (so the nodal gyroscopic term vanishes), scaled by
// a factor. Pure functions of the triangle; no global state.

#include <coshell/element/triangle.h>

#include <deal.II/lac/full_matrix.h>

#include <array>

namespace coshell::element
{
  enum class MassMatrix
  {
    consistent, ///< rho h A / 12 (1 + delta_ij) I per vertex pair
    lumped      ///< rho h A / 3 I per vertex
  };

  struct MassProperties
  {
    double density   = 0; ///< mass per volume
    double thickness = 0; ///< length
    /// Dimensionless factor on the rotary inertia rho h^3/12 (>= 0).
    double     rotary_inertia_factor = 1;
    MassMatrix type                  = MassMatrix::consistent;
  };

  /// The rotary inertia of one vertex: factor * rho h^3 / 12 * A / 3.
  double vertex_rotary_inertia(double area, const MassProperties &mass);

  /// The few distinct entries of the mass matrix below: 'translational'[a][b]
  /// times the 3x3 identity couples the translations of vertices a and b,
  /// 'rotary' is each rotation's diagonal entry (no other entry is
  /// nonzero). An 18x18 product with the matrix is 27 + 9 multiply-adds
  /// with these.
  struct MassEntries
  {
    std::array<std::array<double, 3>, 3> translational{};
    double                               rotary = 0;
  };
  MassEntries shell_mass_entries(const SpatialTriangle &triangle,
                                 const MassProperties  &mass);

  /// 18x18 mass matrix of the triangle in global axes, DoF order 6*vertex +
  /// component (translations then rotations). Translational rows give the
  /// exact rigid-body mass rho h A in every direction.
  dealii::FullMatrix<double> shell_mass(const SpatialTriangle &triangle,
                                        const MassProperties  &mass);
  /// The same into 'matrix' (made 18x18), without allocating where it has
  /// that size already.
  void shell_mass(const SpatialTriangle      &triangle,
                  const MassProperties       &mass,
                  dealii::FullMatrix<double> &matrix);

  /// Viscous drag of a surrounding medium on the triangle, lumped to its
  /// vertices: per unit area -c_n (v.n) n - c_t (v - (v.n) n), with the
  /// triangle's unit normal n. Returns the 9x9 matrix C (translations,
  /// index 3*vertex + component) with f = -C v.
  dealii::FullMatrix<double> drag_matrix(const SpatialTriangle &triangle,
                                         double normal_coefficient,
                                         double tangential_coefficient);
  /// The same into 'matrix' (made 9x9).
  void drag_matrix(const SpatialTriangle      &triangle,
                   double                      normal_coefficient,
                   double                      tangential_coefficient,
                   dealii::FullMatrix<double> &matrix);
} // namespace coshell::element
