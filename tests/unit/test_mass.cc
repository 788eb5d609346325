// Mass and drag kernels of the flat shell triangle.

#include <coshell/element/mass.h>

#include <gtest/gtest.h>

#include <cmath>

namespace
{
  using namespace coshell::element;
  using dealii::Point;

  // A scalene triangle tilted in space, area computed independently.
  const SpatialTriangle triangle = {{Point<3>(0.1, 0.2, 0.3),
                                     Point<3>(1.3, 0.4, 0.1),
                                     Point<3>(0.5, 1.1, 0.9)}};

  double reference_area()
  {
    const auto a = triangle[1] - triangle[0], b = triangle[2] - triangle[0];
    return 0.5 * dealii::cross_product_3d(a, b).norm();
  }

  MassProperties properties(MassMatrix type)
  {
    return {2.0, 0.05, 1.0, type};
  }
} // namespace

TEST(ShellMass, RigidTranslationCarriesTheWholeMass)
{
  for (const MassMatrix type : {MassMatrix::consistent, MassMatrix::lumped})
  {
    const auto   m    = shell_mass(triangle, properties(type));
    const double mass = 2.0 * 0.05 * reference_area();
    for (unsigned int d = 0; d < 3; ++d)
    {
      // v = e_d at every vertex: sum of M v over the d rows = total mass.
      double total = 0;
      for (unsigned int a = 0; a < 3; ++a)
        for (unsigned int b = 0; b < 3; ++b)
          total += m(6 * a + d, 6 * b + d);
      EXPECT_NEAR(total, mass, 1e-14);
    }
  }
}

TEST(ShellMass, ConsistentMassIntegratesLinearFieldsExactly)
{
  // Kinetic energy of a velocity linear in space, v = x_1 (first
  // coordinate) along z: 1/2 rho h int x^2 dA, with the exact integral
  // A/6 (x_a^2 + x_b^2 + x_c^2 + x_a x_b + x_b x_c + x_c x_a).
  const auto   m  = shell_mass(triangle, properties(MassMatrix::consistent));
  const double xa = triangle[0][0], xb = triangle[1][0], xc = triangle[2][0];
  const double exact =
      0.5 * 2.0 * 0.05 * reference_area() / 6 *
      (xa * xa + xb * xb + xc * xc + xa * xb + xb * xc + xc * xa);
  const double v[3]   = {xa, xb, xc};
  double       energy = 0;
  for (unsigned int a = 0; a < 3; ++a)
    for (unsigned int b = 0; b < 3; ++b)
      energy += 0.5 * v[a] * m(6 * a + 2, 6 * b + 2) * v[b];
  EXPECT_NEAR(energy, exact, 1e-14);
}

TEST(ShellMass, RotaryInertiaIsIsotropicAndScaled)
{
  MassProperties p        = properties(MassMatrix::lumped);
  p.rotary_inertia_factor = 3;
  const auto   m          = shell_mass(triangle, p);
  const double J = 3 * 2.0 * std::pow(0.05, 3) / 12 * reference_area() / 3;
  for (unsigned int a = 0; a < 3; ++a)
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        EXPECT_NEAR(m(6 * a + 3 + i, 6 * a + 3 + j), i == j ? J : 0, 1e-18);
  EXPECT_DOUBLE_EQ(vertex_rotary_inertia(reference_area(), p), J);
}

TEST(DragMatrix, SplitsNormalAndTangentialVelocity)
{
  const double cn = 5, ct = 0.5;
  const auto   c = drag_matrix(triangle, cn, ct);
  auto         n = dealii::cross_product_3d(triangle[1] - triangle[0],
                                            triangle[2] - triangle[0]);
  n /= n.norm();
  const double third = reference_area() / 3;
  // A normal velocity meets c_n, an in-plane one c_t, at every vertex.
  const auto t =
      (triangle[1] - triangle[0]) / (triangle[1] - triangle[0]).norm();
  for (unsigned int a = 0; a < 3; ++a)
    for (unsigned int i = 0; i < 3; ++i)
    {
      double normal_force = 0, tangential_force = 0;
      for (unsigned int j = 0; j < 3; ++j)
      {
        normal_force += c(3 * a + i, 3 * a + j) * n[j];
        tangential_force += c(3 * a + i, 3 * a + j) * t[j];
      }
      EXPECT_NEAR(normal_force, third * cn * n[i], 1e-14);
      EXPECT_NEAR(tangential_force, third * ct * t[i], 1e-14);
    }
}

// The entries the inertia's sparse products take are all of the matrix: the
// matrix built from them alone has every nonzero entry of the dense one
// with its value, and nothing else (both mass types).
TEST(ShellMass, EntriesAreTheWholeMatrix)
{
  for (const MassMatrix type : {MassMatrix::consistent, MassMatrix::lumped})
  {
    const auto        m       = shell_mass(triangle, properties(type));
    const MassEntries entries = shell_mass_entries(triangle, properties(type));
    const double      mass    = 2.0 * 0.05 * reference_area();
    for (unsigned int i = 0; i < 18; ++i)
      for (unsigned int j = 0; j < 18; ++j)
      {
        const unsigned int a = i / 6, b = j / 6, d = i % 6, e = j % 6;
        double             expected = 0;
        if (d < 3 && d == e)
          expected = entries.translational[a][b];
        else if (d >= 3 && i == j)
          expected = entries.rotary;
        EXPECT_EQ(m(i, j), expected) << i << ", " << j;
      }
    // All the pair weights together: the whole mass rho h A.
    double total = 0;
    for (const auto &row : entries.translational)
      for (const double w : row)
        total += w;
    EXPECT_NEAR(total, mass, 1e-14 * mass);
  }
}
