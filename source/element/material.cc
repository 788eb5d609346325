#include <coshell/element/material.h>

#include <sstream>
#include <stdexcept>

namespace coshell::element
{
  namespace
  {
    [[noreturn]] void reject(const std::string &quantity,
                             double             value,
                             const std::string &requirement)
    {
      std::ostringstream message;
      message << quantity << " = " << value << ' ' << requirement;
      throw std::invalid_argument(message.str());
    }
  } // namespace

  void ShellMaterial::validate() const
  {
    // Negated comparisons so that NaN is rejected as well.
    if (!(youngs_modulus > 0.0))
      reject("Young's modulus E", youngs_modulus, "must be positive");
    if (!(thickness > 0.0))
      reject("thickness h", thickness, "must be positive");
    // nu -> 0.5 or -1 makes 1 - nu^2 or the shear modulus blow up / vanish.
    if (!(poisson_ratio > -1.0 && poisson_ratio < 0.5))
      reject("Poisson's ratio", poisson_ratio, "is outside (-1, 0.5)");
    if (!(density >= 0.0))
      reject("density", density, "must be non-negative");
  }

  double ShellMaterial::membrane_rigidity() const
  {
    return youngs_modulus * thickness / (1.0 - poisson_ratio * poisson_ratio);
  }

  double ShellMaterial::bending_rigidity() const
  {
    return membrane_rigidity() * thickness * thickness / 12.0;
  }

  double ShellMaterial::shear_modulus() const
  {
    return youngs_modulus / (2.0 * (1.0 + poisson_ratio));
  }

  dealii::FullMatrix<double> plane_stress_matrix(double rigidity,
                                                 double poisson_ratio)
  {
    dealii::FullMatrix<double> matrix(3, 3);
    matrix(0, 0) = rigidity;
    matrix(1, 1) = rigidity;
    matrix(0, 1) = rigidity * poisson_ratio;
    matrix(1, 0) = rigidity * poisson_ratio;
    matrix(2, 2) = rigidity * (1.0 - poisson_ratio) / 2.0;
    return matrix;
  }
} // namespace coshell::element
