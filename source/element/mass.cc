#include <coshell/element/mass.h>

namespace coshell::element
{
  using namespace dealii;

  double vertex_rotary_inertia(double area, const MassProperties &mass)
  {
    const double h = mass.thickness;
    return mass.rotary_inertia_factor * mass.density * h * h * h / 12 * area /
           3;
  }

  FullMatrix<double> shell_mass(const SpatialTriangle &triangle,
                                const MassProperties  &mass)
  {
    FullMatrix<double> m;
    shell_mass(triangle, mass, m);
    return m;
  }

  MassEntries shell_mass_entries(const SpatialTriangle &triangle,
                                 const MassProperties  &mass)
  {
    const double A          = area(triangle);
    const double areal_mass = mass.density * mass.thickness * A;
    MassEntries  entries;
    for (unsigned int a = 0; a < 3; ++a)
      for (unsigned int b = 0; b < 3; ++b)
        // Integral of L_a L_b over the triangle: A/12 (1 + delta_ab).
        entries.translational[a][b] =
            areal_mass * (mass.type == MassMatrix::lumped
                              ? (a == b ? 1.0 / 3 : 0.0)
                              : (a == b ? 2.0 / 12 : 1.0 / 12));
    entries.rotary = vertex_rotary_inertia(A, mass);
    return entries;
  }

  void shell_mass(const SpatialTriangle &triangle,
                  const MassProperties  &mass,
                  FullMatrix<double>    &m)
  {
    const MassEntries entries = shell_mass_entries(triangle, mass);
    m.reinit(18, 18);
    for (unsigned int a = 0; a < 3; ++a)
    {
      for (unsigned int b = 0; b < 3; ++b)
        for (unsigned int d = 0; d < 3; ++d)
          m(6 * a + d, 6 * b + d) = entries.translational[a][b];
      for (unsigned int d = 0; d < 3; ++d)
        m(6 * a + 3 + d, 6 * a + 3 + d) = entries.rotary;
    }
  }

  FullMatrix<double> drag_matrix(const SpatialTriangle &triangle,
                                 double                 normal_coefficient,
                                 double                 tangential_coefficient)
  {
    FullMatrix<double> c;
    drag_matrix(triangle, normal_coefficient, tangential_coefficient, c);
    return c;
  }

  void drag_matrix(const SpatialTriangle &triangle,
                   double                 normal_coefficient,
                   double                 tangential_coefficient,
                   FullMatrix<double>    &c)
  {
    Tensor<1, 3> n =
        cross_product_3d(triangle[1] - triangle[0], triangle[2] - triangle[0]);
    const double twice_area = n.norm();
    if (twice_area == 0)
      throw DegenerateTriangle("drag on a triangle of zero area");
    n /= twice_area;
    const double third_area = twice_area / 6;
    c.reinit(9, 9);
    for (unsigned int a = 0; a < 3; ++a)
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          c(3 * a + i, 3 * a + j) =
              third_area *
              (tangential_coefficient * (i == j ? 1.0 : 0.0) +
               (normal_coefficient - tangential_coefficient) * n[i] * n[j]);
  }
} // namespace coshell::element
