#include <coshell/element/membrane.h>

#include <deal.II/lac/vector.h>

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace coshell::element
{
  namespace
  {
    using dealii::Vector;

    constexpr unsigned int membrane_dofs = 9;

    // Index of component c (0 = u, 1 = v, 2 = theta_z) of vertex i.
    constexpr unsigned int dof(unsigned int vertex, unsigned int component)
    {
      return 3 * vertex + component;
    }

    // Rows (eps_xx, eps_yy, gamma_xy): constant for linear u, v.
    FullMatrix<double> strain_matrix(const PlanarTriangle &triangle)
    {
      const auto         gradients = barycentric_gradients(triangle);
      FullMatrix<double> strain(3, membrane_dofs);
      for (unsigned int i = 0; i < 3; ++i)
      {
        strain(0, dof(i, 0)) = gradients[i][0];
        strain(1, dof(i, 1)) = gradients[i][1];
        strain(2, dof(i, 0)) = gradients[i][1];
        strain(2, dof(i, 1)) = gradients[i][0];
      }
      return strain;
    }

    // Row giving the in-plane rotation omega = (dv/dx - du/dy) / 2.
    Vector<double> rotation_row(const PlanarTriangle &triangle)
    {
      const auto     gradients = barycentric_gradients(triangle);
      Vector<double> rotation(membrane_dofs);
      for (unsigned int i = 0; i < 3; ++i)
      {
        rotation(dof(i, 0)) = -0.5 * gradients[i][1];
        rotation(dof(i, 1)) = 0.5 * gradients[i][0];
      }
      return rotation;
    }

    FullMatrix<double> membrane_material(const ShellMaterial &material)
    {
      return plane_stress_matrix(material.membrane_rigidity(),
                                 material.poisson_ratio);
    }
  } // namespace

  FullMatrix<double> cst_stiffness(const PlanarTriangle &triangle,
                                   const ShellMaterial  &material)
  {
    const FullMatrix<double> strain = strain_matrix(triangle);
    FullMatrix<double>       stiffness(membrane_dofs, membrane_dofs);
    // membrane_rigidity() already carries h: K = A B^T (E h/(1-nu^2) ...) B.
    stiffness.triple_product(membrane_material(material), strain, strain, true,
                             false, std::abs(signed_area(triangle)));
    return stiffness;
  }

  void add_drilling_penalty(const PlanarTriangle &triangle,
                            const ShellMaterial  &material,
                            double                factor,
                            FullMatrix<double>   &membrane_stiffness)
  {
    if (!(factor >= 0.0))
    {
      std::ostringstream message;
      message << "drilling penalty factor = " << factor
              << " must be non-negative";
      throw std::invalid_argument(message.str());
    }
    if (membrane_stiffness.m() != membrane_dofs ||
        membrane_stiffness.n() != membrane_dofs)
      throw std::invalid_argument("add_drilling_penalty expects a 9x9 matrix");

    const double penalty = factor * material.youngs_modulus *
                           material.thickness *
                           std::abs(signed_area(triangle)) / 3.0;
    const Vector<double> rotation = rotation_row(triangle);

    // E_drill = k/2 sum_i (g_i . u)^2 with g_i . u = theta_zi - omega.
    for (unsigned int i = 0; i < 3; ++i)
    {
      Vector<double> mismatch = rotation;
      mismatch *= -1.0;
      mismatch(dof(i, 2)) += 1.0;
      for (unsigned int a = 0; a < membrane_dofs; ++a)
        for (unsigned int b = 0; b < membrane_dofs; ++b)
          membrane_stiffness(a, b) += penalty * mismatch(a) * mismatch(b);
    }
  }

  MembraneForces cst_membrane_forces(const PlanarTriangle        &triangle,
                                     const ShellMaterial         &material,
                                     const MembraneDisplacements &dofs)
  {
    const Vector<double> displacements(dofs.begin(), dofs.end());
    Vector<double>       strain(3);
    strain_matrix(triangle).vmult(strain, displacements);
    Vector<double> forces(3);
    membrane_material(material).vmult(forces, strain);
    return {{forces(0), forces(1), forces(2)}};
  }
} // namespace coshell::element
