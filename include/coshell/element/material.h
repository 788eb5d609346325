#pragma once

#include <deal.II/lac/full_matrix.h>

#include <string>

namespace coshell::element
{
  /// Isotropic linear-elastic shell material. Pure data; no deal.II state.
  struct ShellMaterial
  {
    double youngs_modulus = 1.0;
    double poisson_ratio  = 0.0;
    double thickness      = 1.0;
    double density        = 0.0;

    /// Throws std::invalid_argument naming the offending quantity when
    /// E <= 0, h <= 0, nu outside (-1, 0.5) or density < 0.
    void validate() const;

    /// A = E h / (1 - nu^2), the in-plane (membrane) rigidity.
    double membrane_rigidity() const;
    /// D = E h^3 / (12 (1 - nu^2)), the bending rigidity.
    double bending_rigidity() const;
    double shear_modulus() const;
  };

  /// Isotropic plane-stress matrix
  /// rigidity * [[1,nu,0],[nu,1,0],[0,0,(1-nu)/2]] acting on engineering
  /// components (xx, yy, 2xy). With membrane_rigidity() it maps membrane
  /// strains to N, with bending_rigidity() curvatures to M.
  dealii::FullMatrix<double> plane_stress_matrix(double rigidity,
                                                 double poisson_ratio);
} // namespace coshell::element
