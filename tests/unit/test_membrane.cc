#include <coshell/element/membrane.h>

#include <gtest/gtest.h>

#include "element_test_utilities.h"

using namespace coshell::element;
using namespace coshell::element::testing;

namespace
{
  const PlanarTriangle &generic_triangle = generic_planar_triangle;

  FullMatrix<double> cst_with_drilling(const PlanarTriangle &triangle,
                                       const ShellMaterial  &material)
  {
    FullMatrix<double> stiffness = cst_stiffness(triangle, material);
    add_drilling_penalty(triangle, material, 1e-3, stiffness);
    return stiffness;
  }

  unsigned int count_zero_eigenvalues(const FullMatrix<double> &matrix)
  {
    const auto   eigenvalues = symmetric_eigenvalues(matrix);
    const double largest     = eigenvalues.back();
    return std::count_if(eigenvalues.begin(), eigenvalues.end(),
                         [&](double l)
                         { return std::abs(l) < 1e-10 * largest; });
  }
} // namespace

TEST(Cst, MatchesClosedFormForUnitRightTriangle)
{
  ShellMaterial material;
  material.youngs_modulus       = 2.5;
  material.poisson_ratio        = 0.3;
  material.thickness            = 0.2;
  const PlanarTriangle triangle = {
      {Point<2>(0, 0), Point<2>(1, 0), Point<2>(0, 1)}};

  // Hand-derived: with u = sum N_i u_i, eps_xx = u1 - u0, eps_yy = v2 - v0,
  // gamma = u2 + v1 - u0 - v0, and K = E h A / (1 - nu^2) B^T M B, A = 1/2.
  const double nu = 0.3, alpha = (1 - nu) / 2;
  const double reference[6][6] = {
      {1 + alpha, nu + alpha, -1, -alpha, -alpha, -nu},
      {nu + alpha, 1 + alpha, -nu, -alpha, -alpha, -1},
      {-1, -nu, 1, 0, 0, nu},
      {-alpha, -alpha, 0, alpha, alpha, 0},
      {-alpha, -alpha, 0, alpha, alpha, 0},
      {-nu, -1, nu, 0, 0, 1}};
  const double scale = 2.5 * 0.2 / (2 * (1 - nu * nu));

  const FullMatrix<double> stiffness = cst_stiffness(triangle, material);
  ASSERT_EQ(stiffness.m(), 9u);
  ASSERT_EQ(stiffness.n(), 9u);
  // Translational DOF k of the 6x6 reference is membrane DOF 3 (k/2) + k%2.
  for (unsigned int a = 0; a < 6; ++a)
    for (unsigned int b = 0; b < 6; ++b)
      EXPECT_NEAR(stiffness(3 * (a / 2) + a % 2, 3 * (b / 2) + b % 2),
                  scale * reference[a][b], 1e-14)
          << "entry " << a << ", " << b;
  // Drilling rows and columns stay empty until add_drilling_penalty().
  for (unsigned int i = 0; i < 3; ++i)
    for (unsigned int b = 0; b < 9; ++b)
    {
      EXPECT_EQ(stiffness(3 * i + 2, b), 0.0);
      EXPECT_EQ(stiffness(b, 3 * i + 2), 0.0);
    }
}

TEST(Cst, IsSymmetricWithAndWithoutDrilling)
{
  EXPECT_LT(
      relative_asymmetry(cst_stiffness(generic_triangle, test_material())),
      1e-14);
  EXPECT_LT(
      relative_asymmetry(cst_with_drilling(generic_triangle, test_material())),
      1e-14);
}

TEST(Cst, ClockwiseVertexOrderGivesTheSameStiffness)
{
  expect_independent_of_orientation(
      [](const PlanarTriangle &triangle)
      { return cst_with_drilling(triangle, test_material()); });
}

TEST(Cst, RigidModesCostNothingWithDrillingPenalty)
{
  const auto stiffness = cst_with_drilling(generic_triangle, test_material());
  // Two translations and the in-plane rotation with theta_z = omega.
  const double modes[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (const auto &mode : modes)
  {
    Vector<double> r(9);
    for (unsigned int i = 0; i < 3; ++i)
    {
      const Point<2> &p = generic_triangle[i];
      r(3 * i)          = mode[0] - mode[2] * p[1];
      r(3 * i + 1)      = mode[1] + mode[2] * p[0];
      r(3 * i + 2)      = mode[2];
    }
    EXPECT_LT(relative_residual(stiffness, r), 1e-14);
  }
}

TEST(Cst, DrillingPenaltyLeavesExactlyTheRigidNullSpace)
{
  // Without the penalty the three theta_z are free as well.
  EXPECT_EQ(
      count_zero_eigenvalues(cst_stiffness(generic_triangle, test_material())),
      6u);
  EXPECT_EQ(count_zero_eigenvalues(
                cst_with_drilling(generic_triangle, test_material())),
            3u);
}

TEST(Cst, DrillingPenaltyEnergyOfALoneNodalRotation)
{
  const ShellMaterial material = test_material();
  FullMatrix<double>  penalty(9, 9);
  add_drilling_penalty(generic_triangle, material, 0.02, penalty);
  // theta_z1 = 1, everything else 0: omega = 0, so 2 E = k * 1^2.
  Vector<double> theta(9);
  theta(5)       = 1.0;
  const double k = 0.02 * material.youngs_modulus * material.thickness *
                   signed_area(generic_triangle) / 3.0;
  EXPECT_NEAR(penalty.matrix_norm_square(theta), k, 1e-12 * k);
  EXPECT_THROW(add_drilling_penalty(generic_triangle, material, -1.0, penalty),
               std::invalid_argument);
}

TEST(Cst, MembraneForcesOfALinearFieldAreExact)
{
  const LinearInPlaneField field;
  const ShellMaterial      material = test_material();
  const auto               forces   = cst_membrane_forces(
                      generic_triangle, material, nodal_values(generic_triangle, field));
  const auto exact = field.forces(material);
  for (unsigned int c = 0; c < 3; ++c)
    EXPECT_NEAR(forces[c], exact[c], 1e-12 * std::abs(exact[0]));
}

TEST(Cst, PassesPatchTestOnDistortedPatch)
{
  expect_membrane_patch_test(cst_with_drilling, cst_membrane_forces);
}
