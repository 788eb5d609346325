#pragma once

#include <coshell/element/material.h>
#include <coshell/element/triangle.h>

#include <deal.II/lac/full_matrix.h>

#include <array>

namespace coshell::element
{
  using dealii::FullMatrix;

  /// In-plane stress resultants (Nxx, Nyy, Nxy), force per unit length.
  using MembraneForces = std::array<double, 3>;

  /// Membrane DOFs of one triangle in its frame, node by node:
  /// (u_0, v_0, theta_z0, u_1, v_1, theta_z1, u_2, v_2, theta_z2),
  /// theta_z being the drilling rotation about the element normal.
  using MembraneDisplacements = std::array<double, 9>;

  /// Constant-strain triangle: K = h A B^T C B with
  /// C = E/(1-nu^2) [[1,nu,0],[nu,1,0],[0,0,(1-nu)/2]], returned on the 9
  /// membrane DOFs above. The drilling rows/columns are zero here; see
  /// add_drilling_penalty().
  FullMatrix<double> cst_stiffness(const PlanarTriangle &triangle,
                                   const ShellMaterial  &material);

  /// Drilling penalty that ties each nodal theta_z to the element's
  /// in-plane rotation omega = (dv/dx - du/dy)/2 (Hughes & Brezzi 1989):
  ///   E_drill = 1/2 k sum_i (theta_zi - omega)^2,  k = factor * E h A / 3.
  /// Rigid in-plane rotations (theta_zi = omega) cost nothing, so the
  /// rigid-body null space is untouched, while a nodal theta_z alone is
  /// resisted: flat meshes are no longer singular.
  void add_drilling_penalty(const PlanarTriangle &triangle,
                            const ShellMaterial  &material,
                            double                factor,
                            FullMatrix<double>   &membrane_stiffness);

  /// Constant membrane forces of a CST from its membrane DOFs.
  MembraneForces cst_membrane_forces(const PlanarTriangle        &triangle,
                                     const ShellMaterial         &material,
                                     const MembraneDisplacements &dofs);

  /// The "optimal" ANDES membrane triangle with corner drilling freedoms
  /// (Felippa 2003, CMAME 192:2125), on the 9 membrane DOFs above, theta_z
  /// counter-clockwise about the plane's normal:
  ///   K = K_b + K_h.
  /// K_b = L C L^T / A is the basic stiffness: L (9x3) lumps a constant
  /// stress resultant into nodal forces and moments through edge
  /// displacements that are linear plus an Allman-type bubble in the
  /// drilling rotations (alpha_b = 3/2). K_h = 9/4 beta_0 T^T K_theta T acts
  /// on the hierarchical rotations theta_i - theta_0 (theta_0: the rotation
  /// of the linear part) through corner natural strains (2A/3) beta_k / l^2
  /// with beta_1..9 = (1, 2, 1, 0, 1, -1, -1, -1, -2) and
  /// beta_0 = max((1 - 4 nu^2)/2, 0.01). Rank 6 (the 3 rigid modes cost
  /// nothing), passes the patch test, and a rectangle of two triangles
  /// stores the exact energy in in-plane pure bending for any aspect ratio.
  /// Either vertex order. Throws DegenerateTriangle like the CST.
  /// Dimensionless multipliers of the ANDES membrane's drilling terms: 1
  /// and 1 is Felippa's optimal element. ShellModel lowers both on the
  /// facets of a curved mesh, where they lock (doc/theory.md, section 14).
  struct AndesScales
  {
    double higher_order   = 1.0; ///< multiplies K_h
    double basic_drilling = 1.0; ///< multiplies alpha_b of K_b
  };

  /// `scales` multiply K_h and alpha_b (ShellElementOptions). With
  /// alpha_b scaled the basic part still passes the patch test (alpha_b is a
  /// free parameter of the template; 0 makes K_b the CST's).
  FullMatrix<double> andes_stiffness(const PlanarTriangle &triangle,
                                     const ShellMaterial  &material,
                                     const AndesScales    &scales = {});

  /// Centroidal membrane forces of the ANDES triangle: the constant stress
  /// of the basic part, N = C L^T u / A. The higher-order strains only
  /// stabilise the element; they are not reported.
  MembraneForces andes_membrane_forces(const PlanarTriangle        &triangle,
                                       const ShellMaterial         &material,
                                       const MembraneDisplacements &dofs,
                                       const AndesScales &scales = {});
} // namespace coshell::element
