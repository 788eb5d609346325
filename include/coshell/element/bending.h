#pragma once

#include <coshell/element/material.h>
#include <coshell/element/triangle.h>

#include <deal.II/lac/full_matrix.h>

#include <array>
#include <vector>

namespace coshell::element
{
  using dealii::FullMatrix;

  /// Bending moments (Mxx, Myy, Mxy), moment per unit length, with
  /// M = D [[1,nu,0],[nu,1,0],[0,0,(1-nu)/2]] kappa and
  /// kappa = (-w_xx, -w_yy, -2 w_xy).
  using BendingMoments = std::array<double, 3>;

  /// Bending DOFs node by node: (w_0, theta_x0, theta_y0, w_1, ...), with
  /// right-handed rotations about the frame axes, so that for a
  /// Kirchhoff plate theta_x = dw/dy and theta_y = -dw/dx.
  using BendingDisplacements = std::array<double, 9>;

  enum class BendingElement
  {
    dkt,          ///< Discrete Kirchhoff Triangle (Batoz, Bathe & Ho 1980)
    przemieniecki ///< the paper's modified incomplete cubic
  };

  /// Discrete Kirchhoff Triangle, integrated exactly (3-point rule).
  FullMatrix<double> dkt_stiffness(const PlanarTriangle &triangle,
                                   const ShellMaterial  &material);

  /// The paper's element: w = c1 + c2 x + c3 y + c4 x^2 + c5 xy + c6 y^2
  /// + c7 x^3 + c8 xy^2 + c9 y^3 in the coordinates given (the caller
  /// chooses the frame; the paper puts x along edge AB), nodal DOFs
  /// (w, dw/dy, -dw/dx), curvatures sampled at the three edge midpoints
  /// with weight A/3 each. Throws DegenerateTriangle if the 9x9
  /// interpolation matrix C is singular for this geometry.
  FullMatrix<double> przemieniecki_stiffness(const PlanarTriangle &triangle,
                                             const ShellMaterial  &material);

  /// Curvature-displacement matrices of each element at the given points
  /// of the triangle: 3x9 matrices B with kappa = B u for the bending DOFs
  /// u. Both elements have curvatures linear over the triangle, which is
  /// what bending_stiffness() and bending_moments() build on.
  std::vector<FullMatrix<double>>
  dkt_curvature_matrices(const PlanarTriangle        &triangle,
                         const std::vector<Point<2>> &points);
  /// Throws DegenerateTriangle like przemieniecki_stiffness().
  std::vector<FullMatrix<double>>
  przemieniecki_curvature_matrices(const PlanarTriangle        &triangle,
                                   const std::vector<Point<2>> &points);

  FullMatrix<double> bending_stiffness(BendingElement        type,
                                       const PlanarTriangle &triangle,
                                       const ShellMaterial  &material);

  /// Bending moments at the centroid.
  BendingMoments bending_moments(BendingElement              type,
                                 const PlanarTriangle       &triangle,
                                 const ShellMaterial        &material,
                                 const BendingDisplacements &dofs);
} // namespace coshell::element
