#pragma once

#include <coshell/element/material.h>
#include <coshell/element/triangle.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <array>

namespace coshell::element
{
  /// Compressible neo-Hookean solid in the form CalculiX and Abaqus use,
  ///   W = c10 (J^{-2/3} I1 - 3) + (J - 1)^2 / d1,
  /// with I1 = tr C and J = det F. Matching the peer's law makes the strip
  /// comparison of doc/theory.md a test of the shell, not of two laws.
  /// At small strain it is Hooke's law with mu = 2 c10 and K = 2 / d1.
  struct NeoHookeanLaw
  {
    double c10 = 0.0; ///< MPa
    double d1  = 0.0; ///< 1/MPa

    /// c10 = E / (4 (1 + nu)), d1 = 6 (1 - 2 nu) / E. Validates the
    /// material first (nu < 0.5: an incompressible solid has no d1).
    static NeoHookeanLaw from_material(const ShellMaterial &material);

    /// W(I1, J) in MPa; +infinity when J <= 0 (an inverted solid), so an
    /// energy line search rejects the step.
    double energy_density(double first_invariant, double volume_ratio) const;
  };

  /// Unknowns of one ThickMembrane: the three vertex positions (index
  /// 3 * vertex + axis) and then the three vertex thickness stretches
  /// lambda = h / h0 (index 9 + vertex).
  constexpr unsigned int thick_membrane_dofs = 12;

  /// The membrane of a triangle whose thickness may change: the
  /// three-dimensional law on the stretch of a constant-strain triangle in
  /// its plane and the thickness stretch lambda through it, with no
  /// plane-stress assumption. Where nothing presses on the faces, the
  /// equilibrium of lambda is the plane-stress condition sigma_33 = 0 and
  /// the small-strain stiffness is the CST's; where contact presses on the
  /// faces, lambda is what that pressure and the law give, and the volume
  /// change obeys nu.
  ///
  /// The in-plane metric g = F^T F (F = dx/dX, 3 x 2, constant on the
  /// triangle) is exact for any rigid motion, so no co-rotated frame is
  /// needed. lambda is linear on the triangle and integrated with the
  /// vertex (nodal) rule, so each vertex's stretch enters only through its
  /// own weight A0 h0 / 3: the lambda block of the Hessian is diagonal and
  /// has no zero-energy pattern.
  class ThickMembrane
  {
  public:
    /// `reference` is the undeformed triangle in its own plane,
    /// `reference_thickness` h0 in mm.
    ThickMembrane(const PlanarTriangle &reference,
                  double                reference_thickness,
                  const NeoHookeanLaw  &law);

    /// Stored energy in N mm; +infinity when a vertex stretch or the
    /// in-plane area ratio is not positive.
    double energy(const SpatialTriangle       &positions,
                  const std::array<double, 3> &stretches) const;

    /// The energy's gradient (12) and Hessian (12 x 12) with respect to
    /// the unknowns above. Throws std::domain_error when the energy is
    /// infinite there.
    void derivatives(const SpatialTriangle       &positions,
                     const std::array<double, 3> &stretches,
                     dealii::Vector<double>      &gradient,
                     dealii::FullMatrix<double>  &hessian) const;

    /// Reference area A0 in mm^2.
    double reference_area() const
    {
      return area_;
    }

  private:
    std::array<Tensor<1, 2>, 3> shape_gradients_;
    double                      area_;
    double                      thickness_;
    NeoHookeanLaw               law_;
  };
} // namespace coshell::element
