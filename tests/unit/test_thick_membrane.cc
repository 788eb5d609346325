#include <coshell/element/membrane.h>
#include <coshell/element/thick_membrane.h>

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "element_test_utilities.h"

using namespace coshell::element;
using namespace coshell::element::testing;

namespace
{
  // The intraocular lens's acrylic: E = 1 MPa, nu = 0.42, h0 = 0.8 mm.
  ShellMaterial lens_material()
  {
    ShellMaterial material;
    material.youngs_modulus = 1.0;
    material.poisson_ratio  = 0.42;
    material.thickness      = 0.8;
    return material;
  }

  ThickMembrane generic_membrane()
  {
    const ShellMaterial material = lens_material();
    return ThickMembrane(generic_planar_triangle, material.thickness,
                         NeoHookeanLaw::from_material(material));
  }

  // The generic triangle in space: stretched, sheared, lifted and tilted.
  SpatialTriangle deformed_triangle()
  {
    SpatialTriangle triangle;
    for (unsigned int v = 0; v < 3; ++v)
    {
      const Point<2> &X = generic_planar_triangle[v];
      const Point<2>  stretched(1.3 * X[0] + 0.2 * X[1], 0.85 * X[1]);
      triangle[v] = embed(stretched, tilt(), Point<3>(0.4, -1.0, 2.0));
      triangle[v][2] += 0.05 * v;
    }
    return triangle;
  }

  const std::array<double, 3> squeezed_stretches = {{0.7, 0.82, 0.64}};

  /// The squeezed state of the tests with unknown 'dof' (kernel order)
  /// moved by 'step'.
  struct PerturbedState
  {
    SpatialTriangle       positions = deformed_triangle();
    std::array<double, 3> stretches = squeezed_stretches;

    PerturbedState(unsigned int dof, double step)
    {
      if (dof < 9)
        positions[dof / 3][dof % 3] += step;
      else
        stretches[dof - 9] += step;
    }
  };

  double
  perturbed_energy(const ThickMembrane &membrane, unsigned int dof, double step)
  {
    const PerturbedState state(dof, step);
    return membrane.energy(state.positions, state.stretches);
  }

  dealii::Vector<double> perturbed_gradient(const ThickMembrane &membrane,
                                            unsigned int         dof,
                                            double               step)
  {
    const PerturbedState       state(dof, step);
    dealii::Vector<double>     gradient;
    dealii::FullMatrix<double> hessian;
    membrane.derivatives(state.positions, state.stretches, gradient, hessian);
    return gradient;
  }

  // The embedded reference triangle: positions equal to (X, Y, 0).
  SpatialTriangle flat_reference()
  {
    SpatialTriangle triangle;
    for (unsigned int v = 0; v < 3; ++v)
      triangle[v] = Point<3>(generic_planar_triangle[v][0],
                             generic_planar_triangle[v][1], 0.0);
    return triangle;
  }

  // Cauchy stress of the CalculiX neo-Hooke law under the homogeneous
  // stretches (lp, lp, l3), written from the textbook formula
  // sigma = 2 c10 J^{-5/3} (b - I1/3 1) + 2 (J - 1) / d1 1,
  // independently of the kernel: returns (sigma_11, sigma_33).
  std::array<double, 2>
  uniaxial_cauchy_stress(const NeoHookeanLaw &law, double lp, double l3)
  {
    const double J          = lp * lp * l3;
    const double I1         = 2 * lp * lp + l3 * l3;
    const double deviatoric = 2 * law.c10 * std::pow(J, -5.0 / 3.0);
    const double pressure   = 2 * (J - 1) / law.d1;
    return {{deviatoric * (lp * lp - I1 / 3) + pressure,
             deviatoric * (l3 * l3 - I1 / 3) + pressure}};
  }

  // The in-plane stretch with sigma_11 = 0 for a given l3, by bisection.
  double free_in_plane_stretch(const NeoHookeanLaw &law, double l3)
  {
    double low = 0.5, high = 2.0;
    for (unsigned int i = 0; i < 200; ++i)
    {
      const double middle = 0.5 * (low + high);
      (uniaxial_cauchy_stress(law, middle, l3)[0] > 0 ? high : low) = middle;
    }
    return 0.5 * (low + high);
  }
} // namespace

TEST(NeoHookeanLaw, ParametersFromYoungsModulusAndPoissonsRatio)
{
  const NeoHookeanLaw law = NeoHookeanLaw::from_material(lens_material());
  // mu = E / (2 (1 + nu)) = 2 c10 and K = E / (3 (1 - 2 nu)) = 2 / d1.
  EXPECT_NEAR(2 * law.c10, 1.0 / (2 * 1.42), 1e-15);
  EXPECT_NEAR(2 / law.d1, 1.0 / (3 * 0.16), 1e-12);
  EXPECT_EQ(law.energy_density(3.0, 1.0), 0.0);
  EXPECT_TRUE(std::isinf(law.energy_density(3.0, 0.0)));
}

TEST(NeoHookeanLaw, AnIncompressibleMaterialIsRefused)
{
  ShellMaterial material = lens_material();
  material.poisson_ratio = 0.5;
  EXPECT_THROW(NeoHookeanLaw::from_material(material), std::invalid_argument);
}

TEST(ThickMembrane, GradientIsTheDerivativeOfTheEnergy)
{
  const ThickMembrane        membrane  = generic_membrane();
  const SpatialTriangle      positions = deformed_triangle();
  dealii::Vector<double>     gradient;
  dealii::FullMatrix<double> hessian;
  membrane.derivatives(positions, squeezed_stretches, gradient, hessian);
  const double step = 1e-6;
  for (unsigned int k = 0; k < thick_membrane_dofs; ++k)
  {
    const double difference = (perturbed_energy(membrane, k, step) -
                               perturbed_energy(membrane, k, -step)) /
                              (2 * step);
    EXPECT_NEAR(gradient(k), difference, 1e-6 * gradient.linfty_norm())
        << "unknown " << k;
  }
}

TEST(ThickMembrane, HessianIsTheDerivativeOfTheGradient)
{
  const ThickMembrane        membrane  = generic_membrane();
  const SpatialTriangle      positions = deformed_triangle();
  dealii::Vector<double>     gradient;
  dealii::FullMatrix<double> hessian;
  membrane.derivatives(positions, squeezed_stretches, gradient, hessian);
  EXPECT_LT(relative_asymmetry(hessian), 1e-14);
  const double step = 1e-6;
  for (unsigned int l = 0; l < thick_membrane_dofs; ++l)
  {
    dealii::Vector<double> difference = perturbed_gradient(membrane, l, step);
    difference.add(-1.0, perturbed_gradient(membrane, l, -step));
    difference /= 2 * step;
    for (unsigned int k = 0; k < thick_membrane_dofs; ++k)
      EXPECT_NEAR(hessian(k, l), difference(k), 1e-6 * hessian.frobenius_norm())
          << "entry " << k << ", " << l;
  }
}

TEST(ThickMembrane, RigidMotionsStoreNoEnergy)
{
  const ThickMembrane membrane = generic_membrane();
  SpatialTriangle     moved;
  for (unsigned int v = 0; v < 3; ++v)
    moved[v] =
        embed(generic_planar_triangle[v], tilt(), Point<3>(3.0, -2.0, 0.5));
  const std::array<double, 3> unstretched = {{1.0, 1.0, 1.0}};
  EXPECT_NEAR(membrane.energy(moved, unstretched), 0.0, 1e-15);
  dealii::Vector<double>     gradient;
  dealii::FullMatrix<double> hessian;
  membrane.derivatives(moved, unstretched, gradient, hessian);
  EXPECT_LT(gradient.linfty_norm(), 1e-14);

  // The same deformed state, rotated and moved, stores the same energy.
  SpatialTriangle turned = deformed_triangle();
  const auto rotation    = rotation_matrix(Tensor<1, 3>({-0.2, 0.9, 0.4}), 2.3);
  for (auto &vertex : turned)
    vertex = Point<3>(rotation * vertex) + Tensor<1, 3>({1.0, 2.0, 3.0});
  EXPECT_NEAR(membrane.energy(turned, squeezed_stretches),
              membrane.energy(deformed_triangle(), squeezed_stretches),
              1e-13 * membrane.energy(deformed_triangle(), squeezed_stretches));
}

// With the thickness stretches condensed out (free faces), the small-strain
// stiffness on the in-plane unknowns is the plane-stress CST's: the law's
// sigma_33 = 0 is the shell's plane-stress assumption.
TEST(ThickMembrane, FreeFacesGiveTheConstantStrainTriangle)
{
  const ShellMaterial        material = lens_material();
  const ThickMembrane        membrane = generic_membrane();
  dealii::Vector<double>     gradient;
  dealii::FullMatrix<double> hessian;
  membrane.derivatives(flat_reference(), {{1.0, 1.0, 1.0}}, gradient, hessian);
  const FullMatrix<double> cst =
      cst_stiffness(generic_planar_triangle, material);
  for (unsigned int a = 0; a < 3; ++a)
    for (unsigned int b = 0; b < 3; ++b)
      for (unsigned int i = 0; i < 2; ++i)
        for (unsigned int j = 0; j < 2; ++j)
        {
          double condensed = hessian(3 * a + i, 3 * b + j);
          for (unsigned int v = 0; v < 3; ++v)
            condensed -= hessian(3 * a + i, 9 + v) * hessian(9 + v, 3 * b + j) /
                         hessian(9 + v, 9 + v);
          EXPECT_NEAR(condensed, cst(3 * a + i, 3 * b + j),
                      1e-12 * cst.frobenius_norm());
        }
}

// A small in-plane strain with free faces thins the sheet by
// eps_33 = -nu / (1 - nu) (eps_11 + eps_22): the volume change obeys nu.
TEST(ThickMembrane, FreeFacesThinByPoissonsRatio)
{
  const ThickMembrane membrane = generic_membrane();
  const double        e11 = 2e-5, e22 = -5e-6;
  SpatialTriangle     strained = flat_reference();
  for (auto &vertex : strained)
  {
    vertex[0] *= 1 + e11;
    vertex[1] *= 1 + e22;
  }
  // One Newton step on the (uncoupled) vertex stretches from lambda = 1.
  dealii::Vector<double>     gradient;
  dealii::FullMatrix<double> hessian;
  membrane.derivatives(strained, {{1.0, 1.0, 1.0}}, gradient, hessian);
  const double nu = lens_material().poisson_ratio;
  for (unsigned int v = 0; v < 3; ++v)
  {
    const double eps33 = -gradient(9 + v) / hessian(9 + v, 9 + v);
    EXPECT_NEAR(eps33, -nu / (1 - nu) * (e11 + e22), 1e-4 * std::abs(eps33));
  }
}

// A frictionless squeeze between rigid plates is homogeneous uniaxial
// stress: the plates' force is sigma_33 times the current area, from the
// Cauchy stress formula of the law. Up to 50 % squeeze.
TEST(ThickMembrane, FrictionlessSqueezeIsUniaxialStress)
{
  const ShellMaterial material = lens_material();
  const NeoHookeanLaw law      = NeoHookeanLaw::from_material(material);
  const ThickMembrane membrane = generic_membrane();
  for (const double squeeze : {0.05, 0.3, 0.5})
  {
    const double    l3       = 1 - squeeze;
    const double    lp       = free_in_plane_stretch(law, l3);
    SpatialTriangle expanded = flat_reference();
    for (auto &vertex : expanded)
      vertex = Point<3>(lp * vertex);
    dealii::Vector<double>     gradient;
    dealii::FullMatrix<double> hessian;
    membrane.derivatives(expanded, {{l3, l3, l3}}, gradient, hessian);

    // No in-plane force is left at the free stretch...
    for (unsigned int k = 0; k < 9; ++k)
      EXPECT_LT(std::abs(gradient(k)), 1e-9 * std::abs(gradient(9)));
    // ... and the plates push with dE/dh = sum_v dE/dlambda_v / h0.
    const double plate_force =
        (gradient(9) + gradient(10) + gradient(11)) / material.thickness;
    const double area = membrane.reference_area() * lp * lp;
    EXPECT_NEAR(plate_force, uniaxial_cauchy_stress(law, lp, l3)[1] * area,
                1e-9 * std::abs(plate_force))
        << "squeeze " << squeeze;
  }
}

TEST(ThickMembrane, InvertedOrCrushedStatesHaveInfiniteEnergy)
{
  const ThickMembrane        membrane = generic_membrane();
  dealii::Vector<double>     gradient;
  dealii::FullMatrix<double> hessian;
  EXPECT_TRUE(std::isinf(membrane.energy(deformed_triangle(), {{1, 0, 1}})));
  EXPECT_THROW(membrane.derivatives(deformed_triangle(), {{1, -0.1, 1}},
                                    gradient, hessian),
               std::domain_error);
  SpatialTriangle collapsed = deformed_triangle();
  collapsed[2]              = collapsed[1];
  EXPECT_TRUE(std::isinf(membrane.energy(collapsed, {{1, 1, 1}})));
  EXPECT_THROW(ThickMembrane(generic_planar_triangle, 0.0,
                             NeoHookeanLaw::from_material(lens_material())),
               std::invalid_argument);
}
