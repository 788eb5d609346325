#include <coshell/element/corotational.h>

#include <gtest/gtest.h>

#include <iostream>
#include <random>

#include "element_test_utilities.h"

using namespace coshell::element;
using namespace coshell::element::testing;

namespace
{
  const SpatialTriangle initial_triangle = {{Point<3>(0.1, 0.2, 0.3),
                                             Point<3>(1.2, -0.3, 0.7),
                                             Point<3>(0.4, 0.9, -0.2)}};

  const std::array<BendingElement, 2> both_elements = {
      {BendingElement::dkt, BendingElement::przemieniecki}};

  std::string name(BendingElement type)
  {
    return type == BendingElement::dkt ? "DKT" : "Przemieniecki";
  }

  ShellElementOptions with_bending(BendingElement type, bool membrane = true)
  {
    ShellElementOptions options;
    options.bending = type;
    if (!membrane)
      options.membrane = std::nullopt;
    return options;
  }

  // Thicker than test_material() so that bending and membrane forces are
  // of comparable size and neither hides the other in a norm.
  ShellMaterial thick_material()
  {
    ShellMaterial material = test_material();
    material.thickness     = 0.3;
    return material;
  }

  struct State
  {
    SpatialTriangle x;
    NodalRotations  rotations;
  };

  State initial_state(const SpatialTriangle &triangle)
  {
    const Tensor<2, 3> identity = dealii::unit_symmetric_tensor<3>();
    return {triangle, {{identity, identity, identity}}};
  }

  Tensor<1, 3> random_unit_vector(std::mt19937 &rng)
  {
    std::normal_distribution<double> normal;
    Tensor<1, 3>                     v({normal(rng), normal(rng), normal(rng)});
    return v / v.norm();
  }

  // How far random_deformed_state goes beyond a rigid motion.
  struct Deformation
  {
    double vertex_offset = 0.15; ///< per component, edges are ~1
    double rotation      = 2.15; ///< mean nodal rotation angle (rad)
  };

  // A large rigid rotation Q (1 to 3 rad) and translation, random vertex
  // offsets, and nodal rotations exp(theta_i) Q with |theta_i| within 20%
  // of the given angle (by default 1.7 to 2.6 rad: above 90 degrees, below
  // pi).
  State random_deformed_state(const SpatialTriangle &triangle,
                              unsigned               seed,
                              const Deformation     &deformation = {})
  {
    std::mt19937                           rng(seed);
    std::uniform_real_distribution<double> uniform(-1.0, 1.0);
    const Tensor<2, 3>                     q =
        rotation_matrix(random_unit_vector(rng), 2.0 + uniform(rng));
    const Tensor<1, 3> shift({uniform(rng), uniform(rng), uniform(rng)});

    State state;
    for (unsigned int i = 0; i < 3; ++i)
    {
      const Tensor<1, 3> offset({uniform(rng), uniform(rng), uniform(rng)});
      state.x[i] = Point<3>(
          q * (triangle[i] + deformation.vertex_offset * offset) + shift);
      const double angle = deformation.rotation * (1.0 + 0.2 * uniform(rng));
      state.rotations[i] = rotation_exp(angle * random_unit_vector(rng)) * q;
    }
    return state;
  }

  // The perturbation the element is differentiated for: x_i += du_i,
  // R_i <- exp(skew(dtheta_i)) R_i, DOF index 6 * vertex + component.
  State perturbed(State state, unsigned int dof, double step)
  {
    Tensor<1, 3> direction;
    direction[dof % 3] = step;
    if (dof % 6 < 3)
      state.x[dof / 6] += direction;
    else
      state.rotations[dof / 6] =
          rotation_exp(direction) * state.rotations[dof / 6];
    return state;
  }

  ShellDisplacements
  force(const CorotationalShell &element,
        const State             &state,
        CorotationalTangent      type    = CorotationalTangent::consistent,
        FullMatrix<double>      *tangent = nullptr)
  {
    ShellDisplacements f;
    element.internal_force(state.x, state.rotations, type, f, tangent);
    return f;
  }

  FullMatrix<double> consistent_tangent(const CorotationalShell &element,
                                        const State             &state)
  {
    FullMatrix<double> tangent;
    force(element, state, CorotationalTangent::consistent, &tangent);
    return tangent;
  }

  // Central differences of the force, column b = d f / d p_b.
  FullMatrix<double> finite_difference_tangent(const CorotationalShell &element,
                                               const State             &state,
                                               double                   step)
  {
    FullMatrix<double> tangent(shell_dofs, shell_dofs);
    for (unsigned int b = 0; b < shell_dofs; ++b)
    {
      const ShellDisplacements plus = force(element, perturbed(state, b, step));
      const ShellDisplacements minus =
          force(element, perturbed(state, b, -step));
      for (unsigned int a = 0; a < shell_dofs; ++a)
        tangent(a, b) = (plus[a] - minus[a]) / (2.0 * step);
    }
    return tangent;
  }

  double relative_difference(const FullMatrix<double> &a,
                             const FullMatrix<double> &b)
  {
    FullMatrix<double> difference(a);
    difference.add(-1.0, b);
    return difference.frobenius_norm() / b.frobenius_norm();
  }

  double norm(const ShellDisplacements &a)
  {
    double sum = 0.0;
    for (const double v : a)
      sum += v * v;
    return std::sqrt(sum);
  }

  double max_difference(const ShellDisplacements &a,
                        const ShellDisplacements &b)
  {
    double difference = 0.0;
    for (unsigned int i = 0; i < shell_dofs; ++i)
      difference = std::max(difference, std::abs(a[i] - b[i]));
    return difference;
  }

  // Largest angle of the nodal deformational rotations.
  double largest_rotation(const ShellDisplacements &d)
  {
    double largest = 0.0;
    for (unsigned int i = 0; i < 3; ++i)
      largest = std::max(
          largest,
          Tensor<1, 3>({d[6 * i + 3], d[6 * i + 4], d[6 * i + 5]}).norm());
    return largest;
  }

  // A force scale: what K_l does to DOFs of size one longest edge / one
  // radian.
  double force_scale(const CorotationalShell &element)
  {
    return element.local_stiffness().frobenius_norm() * 1.2;
  }

  // Applies x -> Q x + shift, R_i -> Q R_i.
  State rigidly_moved(const State        &state,
                      const Tensor<2, 3> &q,
                      const Tensor<1, 3> &shift)
  {
    State moved;
    for (unsigned int i = 0; i < 3; ++i)
    {
      moved.x[i]         = Point<3>(q * state.x[i] + shift);
      moved.rotations[i] = q * state.rotations[i];
    }
    return moved;
  }

  // Vertex order (1, 2, 0): new vertex i is old vertex order[i].
  const std::array<unsigned int, 3> cyclic_order = {{1, 2, 0}};

  State renumbered(const State &state)
  {
    State result;
    for (unsigned int i = 0; i < 3; ++i)
    {
      result.x[i]         = state.x[cyclic_order[i]];
      result.rotations[i] = state.rotations[cyclic_order[i]];
    }
    return result;
  }

  SpatialTriangle renumbered(const SpatialTriangle &triangle)
  {
    return {{triangle[cyclic_order[0]], triangle[cyclic_order[1]],
             triangle[cyclic_order[2]]}};
  }

  unsigned int old_dof(unsigned int dof)
  {
    return 6 * cyclic_order[dof / 6] + dof % 6;
  }
} // namespace

TEST(CorotationalShell, ForceIsTheEnergyGradient)
{
  for (const auto type : both_elements)
  {
    const CorotationalShell  element(initial_triangle, thick_material(),
                                     with_bending(type));
    const State              state = random_deformed_state(initial_triangle, 7);
    const ShellDisplacements f     = force(element, state);
    ShellDisplacements       gradient;
    const double             step = 1e-6;
    for (unsigned int b = 0; b < shell_dofs; ++b)
    {
      const State plus  = perturbed(state, b, step);
      const State minus = perturbed(state, b, -step);
      gradient[b]       = (element.energy(plus.x, plus.rotations) -
                     element.energy(minus.x, minus.rotations)) /
                    (2.0 * step);
    }
    EXPECT_LT(max_difference(f, gradient) / norm(f), 1e-7) << name(type);
  }
}

TEST(CorotationalShell, ConsistentTangentMatchesFiniteDifferences)
{
  const std::vector<std::pair<ShellMaterial, bool>> variants = {
      {thick_material(), true},
      {test_material(), true},
      {thick_material(), false}};
  for (const auto type : both_elements)
    for (const auto &[material, membrane] : variants)
    {
      const CorotationalShell element(initial_triangle, material,
                                      with_bending(type, membrane));
      double                  worst = 0.0;
      for (const unsigned seed : {1u, 2u, 3u})
      {
        const State state = random_deformed_state(initial_triangle, seed);
        EXPECT_GT(largest_rotation(
                      element.deformational_dofs(state.x, state.rotations)),
                  M_PI / 2);
        const double error = relative_difference(
            consistent_tangent(element, state),
            finite_difference_tangent(element, state, 1e-6));
        worst = std::max(worst, error);
        EXPECT_LT(error, 1e-6) << name(type) << ", seed " << seed;
      }
      std::cout << name(type) << (membrane ? "" : " bending only")
                << ", h = " << material.thickness
                << ": tangent vs central differences " << worst << std::endl;
    }
}

// Small deformational rotations take the series branches of the rotation
// maps, whose derivatives must be as exact as the closed forms'.
TEST(CorotationalShell, ConsistentTangentIsExactForSmallDeformations)
{
  for (const auto type : both_elements)
    for (const double size : {0.2, 1e-2, 1e-5})
    {
      const CorotationalShell element(initial_triangle, thick_material(),
                                      with_bending(type));
      const State             state =
          random_deformed_state(initial_triangle, 12, {size, size});
      EXPECT_LT(
          relative_difference(consistent_tangent(element, state),
                              finite_difference_tangent(element, state, 1e-6)),
          1e-6)
          << name(type) << ", deformation " << size;
    }
}

// The multiplicative rotation update adds -1/2 skew(m_i) to each nodal
// rotation block of the symmetric Hessian of the energy (m_i the nodal
// moment), so away from equilibrium the consistent tangent is not symmetric.
TEST(CorotationalShell, ConsistentTangentIsNotSymmetricAwayFromEquilibrium)
{
  const CorotationalShell element(initial_triangle, thick_material(),
                                  with_bending(BendingElement::dkt));
  const State             state = random_deformed_state(initial_triangle, 4);
  const double            asymmetry =
      relative_asymmetry(consistent_tangent(element, state));
  std::cout << "consistent tangent asymmetry: " << asymmetry << std::endl;
  EXPECT_GT(asymmetry, 1e-4);
}

TEST(CorotationalShell, IsObjective)
{
  std::mt19937 rng(11);
  for (const auto type : both_elements)
  {
    const CorotationalShell element(initial_triangle, thick_material(),
                                    with_bending(type));
    const State             state = random_deformed_state(initial_triangle, 5);
    const Tensor<2, 3>      q = rotation_matrix(random_unit_vector(rng), 2.4);
    const State moved = rigidly_moved(state, q, Tensor<1, 3>({1.0, -2.0, 0.5}));

    const double energy = element.energy(state.x, state.rotations);
    EXPECT_NEAR(element.energy(moved.x, moved.rotations), energy,
                1e-12 * energy)
        << name(type);

    const ShellDisplacements f       = force(element, state);
    const ShellDisplacements f_moved = force(element, moved);
    ShellDisplacements       rotated;
    for (unsigned int block = 0; block < 6; ++block)
    {
      const Tensor<1, 3> v =
          q * Tensor<1, 3>({f[3 * block], f[3 * block + 1], f[3 * block + 2]});
      for (unsigned int c = 0; c < 3; ++c)
        rotated[3 * block + c] = v[c];
    }
    EXPECT_LT(max_difference(f_moved, rotated), 1e-10 * norm(f)) << name(type);
  }
}

TEST(CorotationalShell, RigidMotionsAreStressFree)
{
  std::mt19937       rng(3);
  const Tensor<1, 3> normal =
      cross_product_3d(initial_triangle[1] - initial_triangle[0],
                       initial_triangle[2] - initial_triangle[0]);
  std::vector<Tensor<2, 3>> rotations = {
      rotation_matrix(normal, M_PI),
      rotation_matrix(initial_triangle[1] - initial_triangle[0], M_PI),
      rotation_matrix(random_unit_vector(rng), M_PI)};
  for (unsigned int k = 0; k < 5; ++k)
    rotations.push_back(rotation_matrix(
        random_unit_vector(rng),
        std::uniform_real_distribution<double>(0.0, M_PI)(rng)));

  for (const auto type : both_elements)
  {
    const CorotationalShell element(initial_triangle, thick_material(),
                                    with_bending(type));
    const double            scale = force_scale(element);
    for (const Tensor<2, 3> &q : rotations)
    {
      const State moved = rigidly_moved(initial_state(initial_triangle), q,
                                        Tensor<1, 3>({0.3, 2.0, -1.0}));
      EXPECT_LT(norm(element.deformational_dofs(moved.x, moved.rotations)),
                1e-12)
          << name(type);
      EXPECT_LT(norm(force(element, moved)), 1e-10 * scale) << name(type);
    }
  }
}

TEST(CorotationalShell, UndeformedTangentIsTheLinearStiffness)
{
  for (const auto type : both_elements)
    for (const bool membrane : {true, false})
    {
      const auto               options = with_bending(type, membrane);
      const CorotationalShell  element(initial_triangle, test_material(),
                                       options);
      const FullMatrix<double> linear =
          shell_stiffness(initial_triangle, test_material(), options);
      const State state = initial_state(initial_triangle);
      EXPECT_LT(relative_difference(consistent_tangent(element, state), linear),
                1e-10)
          << name(type);
      FullMatrix<double> paper;
      force(element, state, CorotationalTangent::paper, &paper);
      EXPECT_LT(relative_difference(paper, linear), 1e-12) << name(type);
    }
}

// f(eps u) = K_lin eps u + O(eps^2): the relative error falls like eps.
TEST(CorotationalShell, SmallDisplacementsGiveTheLinearForce)
{
  ShellDisplacements u;
  for (unsigned int i = 0; i < shell_dofs; ++i)
    u[i] = std::sin(1.0 + 3.7 * i);
  for (const auto type : both_elements)
  {
    const auto               options = with_bending(type);
    const CorotationalShell  element(initial_triangle, thick_material(),
                                     options);
    const FullMatrix<double> linear =
        shell_stiffness(initial_triangle, thick_material(), options);
    for (const double eps : {1e-3, 1e-5})
    {
      State state = initial_state(initial_triangle);
      for (unsigned int i = 0; i < 3; ++i)
      {
        state.x[i] +=
            eps * Tensor<1, 3>({u[6 * i], u[6 * i + 1], u[6 * i + 2]});
        state.rotations[i] = rotation_exp(
            eps * Tensor<1, 3>({u[6 * i + 3], u[6 * i + 4], u[6 * i + 5]}));
      }
      Vector<double> expected(shell_dofs);
      linear.vmult(expected, Vector<double>(u.begin(), u.end()));
      expected *= eps;
      const ShellDisplacements f = force(element, state);
      const double             error =
          max_difference(f,
                         [&]
                         {
                           ShellDisplacements e;
                           std::copy(expected.begin(), expected.end(),
                                     e.begin());
                           return e;
                         }()) /
          expected.linfty_norm();
      EXPECT_LT(error, 20.0 * eps) << name(type) << ", eps " << eps;
      EXPECT_GT(error, 1e-3 * eps) << name(type) << ", eps " << eps;
    }
  }
}

TEST(CorotationalShell, DktIsInvariantToVertexOrder)
{
  for (const bool membrane : {true, false})
  {
    const auto options = with_bending(BendingElement::dkt, membrane);
    const CorotationalShell element(initial_triangle, thick_material(),
                                    options);
    const CorotationalShell cyclic(renumbered(initial_triangle),
                                   thick_material(), options);
    const State             state = random_deformed_state(initial_triangle, 9);
    const State             state_cyclic = renumbered(state);

    const double energy = element.energy(state.x, state.rotations);
    EXPECT_NEAR(cyclic.energy(state_cyclic.x, state_cyclic.rotations), energy,
                1e-10 * energy);

    FullMatrix<double>       tangent, tangent_cyclic;
    const ShellDisplacements f =
        force(element, state, CorotationalTangent::consistent, &tangent);
    const ShellDisplacements f_cyclic = force(
        cyclic, state_cyclic, CorotationalTangent::consistent, &tangent_cyclic);
    for (unsigned int a = 0; a < shell_dofs; ++a)
    {
      EXPECT_NEAR(f_cyclic[a], f[old_dof(a)], 1e-10 * norm(f));
      for (unsigned int b = 0; b < shell_dofs; ++b)
        EXPECT_NEAR(tangent_cyclic(a, b), tangent(old_dof(a), old_dof(b)),
                    1e-10 * tangent.frobenius_norm());
    }
  }
}

// The paper's element depends on which vertex comes first (its polynomial
// is not rotation invariant, see test_shell_element.cc), so the
// co-rotational version inherits it: the same state has another energy.
TEST(CorotationalShell, PrzemienieckiDependsOnVertexOrder)
{
  const auto options = with_bending(BendingElement::przemieniecki, false);
  const CorotationalShell element(initial_triangle, thick_material(), options);
  const CorotationalShell cyclic(renumbered(initial_triangle), thick_material(),
                                 options);
  const State             state = random_deformed_state(initial_triangle, 9);
  const State             state_cyclic = renumbered(state);
  const double            energy = element.energy(state.x, state.rotations);
  const double            change =
      std::abs(cyclic.energy(state_cyclic.x, state_cyclic.rotations) - energy) /
      energy;
  std::cout << "Przemieniecki bending energy, relative change under cyclic "
               "renumbering: "
            << change << std::endl;
  EXPECT_GT(change, 1e-2);
}

// Both membranes: the element keeps its resultants as a linear map of d
// built once (ResultantRecovery); shell_resultants rebuilds them.
TEST(CorotationalShell, ResultantsAreTheLinearOnesOfTheCorotatedDofs)
{
  for (const MembraneElement membrane :
       {MembraneElement::cst, MembraneElement::andes})
  {
    ShellElementOptions options = with_bending(BendingElement::dkt);
    options.membrane            = membrane;
    const CorotationalShell  element(initial_triangle, thick_material(),
                                     options);
    const State              state = random_deformed_state(initial_triangle, 2);
    const ShellDisplacements d =
        element.deformational_dofs(state.x, state.rotations);
    for (unsigned int i = 0; i < 3; ++i)
      EXPECT_EQ(d[6 * i + 2], 0.0);

    // The same DOFs on the initial triangle, in its frame E0.
    const ElementFrame initial_frame = make_element_frame(initial_triangle);
    ShellDisplacements initial_global;
    for (unsigned int block = 0; block < 6; ++block)
    {
      Tensor<1, 3> v;
      for (unsigned int a = 0; a < 3; ++a)
        v += d[3 * block + a] * initial_frame.axes[a];
      for (unsigned int c = 0; c < 3; ++c)
        initial_global[3 * block + c] = v[c];
    }
    const ShellResultants linear = shell_resultants(
        initial_triangle, thick_material(), options, initial_global);
    const ShellResultants corotated =
        element.resultants(state.x, state.rotations);
    for (unsigned int c = 0; c < 3; ++c)
    {
      EXPECT_NEAR(corotated.membrane_local[c], linear.membrane_local[c],
                  1e-12 * std::abs(linear.membrane_local[0]));
      EXPECT_NEAR(corotated.bending_local[c], linear.bending_local[c],
                  1e-12 * std::abs(linear.bending_local[0]));
    }
    // Global tensors: in the current frame, normal to the current triangle.
    const Tensor<1, 3> normal =
        cross_product_3d(state.x[1] - state.x[0], state.x[2] - state.x[0]);
    EXPECT_LT((corotated.membrane_global * normal).norm(),
              1e-12 * corotated.membrane_global.norm() * normal.norm());
    EXPECT_NEAR(corotated.bending_global.norm(), linear.bending_global.norm(),
                1e-12 * linear.bending_global.norm());
  }
}

TEST(CorotationalShell, PaperTangentIsSymmetricAndKeepsTheForce)
{
  const CorotationalShell  element(initial_triangle, thick_material(),
                                   with_bending(BendingElement::dkt));
  const State              state = random_deformed_state(initial_triangle, 6);
  FullMatrix<double>       paper, consistent;
  const ShellDisplacements f_paper =
      force(element, state, CorotationalTangent::paper, &paper);
  const ShellDisplacements f =
      force(element, state, CorotationalTangent::consistent, &consistent);
  EXPECT_LT(max_difference(f_paper, f), 1e-13 * norm(f));
  EXPECT_LT(relative_asymmetry(paper), 1e-14);
  std::cout << "paper vs consistent tangent at a large deformation: "
            << relative_difference(paper, consistent) << std::endl;
}

TEST(CorotationalRotationMaps, ExpAndLogAreInverse)
{
  const Tensor<2, 3> identity = dealii::unit_symmetric_tensor<3>();
  std::mt19937       rng(5);
  for (const double angle : {0.0, 1e-8, 1e-3, 0.1, 1.0, 3.0, M_PI - 1e-6})
    for (unsigned int k = 0; k < 3; ++k)
    {
      const Tensor<1, 3> axis     = random_unit_vector(rng);
      const Tensor<1, 3> theta    = angle * axis;
      const Tensor<2, 3> rotation = rotation_exp(theta);
      EXPECT_LT((transpose(rotation) * rotation - identity).norm(), 4e-15);
      EXPECT_NEAR(determinant(rotation), 1.0, 4e-15);
      EXPECT_LT((rotation - rotation_matrix(axis, angle)).norm(), 4e-15);
      EXPECT_LT((rotation_log(rotation) - theta).norm(),
                4e-15 * std::max(1.0, angle))
          << "angle " << angle;
    }
}

// Near 0 the rotation vector is recovered to relative accuracy: no
// 1 - cos or acos cancellation.
TEST(CorotationalRotationMaps, SmallAnglesKeepRelativeAccuracy)
{
  const Tensor<1, 3> theta({3e-9, -4e-9, 1.2e-8});
  const Tensor<2, 3> rotation = rotation_exp(theta);
  EXPECT_LT((rotation_log(rotation) - theta).norm(), 1e-15 * theta.norm());
  EXPECT_LT((0.5 * (rotation - transpose(rotation)) - skew(theta)).norm(),
            1e-15 * theta.norm());
}

TEST(FollowerPressure, TotalForceAndLoadStiffness)
{
  const double          pressure = -2.5;
  std::array<double, 9> f;
  FullMatrix<double>    stiffness;
  follower_pressure(initial_triangle, pressure, f, &stiffness);

  const Tensor<1, 3> normal =
      cross_product_3d(initial_triangle[1] - initial_triangle[0],
                       initial_triangle[2] - initial_triangle[0]);
  Tensor<1, 3> total;
  for (unsigned int i = 0; i < 3; ++i)
    total += Tensor<1, 3>({f[3 * i], f[3 * i + 1], f[3 * i + 2]});
  const Tensor<1, 3> expected =
      pressure * area(initial_triangle) * normal / normal.norm();
  EXPECT_LT((total - expected).norm(), 1e-14 * expected.norm());

  const double step  = 1e-6;
  double       error = 0.0;
  for (unsigned int b = 0; b < 9; ++b)
  {
    SpatialTriangle plus = initial_triangle, minus = initial_triangle;
    plus[b / 3][b % 3] += step;
    minus[b / 3][b % 3] -= step;
    std::array<double, 9> f_plus, f_minus;
    follower_pressure(plus, pressure, f_plus, nullptr);
    follower_pressure(minus, pressure, f_minus, nullptr);
    for (unsigned int a = 0; a < 9; ++a)
      error = std::max(error, std::abs((f_plus[a] - f_minus[a]) / (2 * step) -
                                       stiffness(a, b)));
  }
  EXPECT_LT(error, 1e-7 * stiffness.frobenius_norm());
}

// K_l comes from shell_stiffness_local, so the ANDES membrane (genuine
// drilling stiffness, no penalty) needs nothing of its own here.
TEST(CorotationalShell, AndesMembraneKeepsTheKernelConsistent)
{
  ShellElementOptions options = with_bending(BendingElement::dkt);
  options.membrane            = MembraneElement::andes;
  const CorotationalShell element(initial_triangle, thick_material(), options);

  const State deformed = random_deformed_state(initial_triangle, 2);
  EXPECT_LT(
      relative_difference(consistent_tangent(element, deformed),
                          finite_difference_tangent(element, deformed, 1e-6)),
      1e-6);

  const State initial = initial_state(initial_triangle);
  EXPECT_LT(relative_difference(
                consistent_tangent(element, initial),
                shell_stiffness(initial_triangle, thick_material(), options)),
            1e-10);

  const State moved = rigidly_moved(
      initial, rotation_matrix(Tensor<1, 3>({0.2, -0.5, 0.8}), 2.0),
      Tensor<1, 3>({0.3, 2.0, -1.0}));
  EXPECT_LT(norm(force(element, moved)), 1e-10 * force_scale(element));
}

// The symmetric tangent is the symmetric part of the consistent one, with
// the same force.
TEST(CorotationalShell, SymmetricTangentIsTheSymmetricPartOfTheConsistent)
{
  const CorotationalShell element(initial_triangle, thick_material(),
                                  with_bending(both_elements[0]));
  const State             state = random_deformed_state(initial_triangle, 5);
  FullMatrix<double>      symmetric;
  const auto              f =
      force(element, state, CorotationalTangent::symmetric, &symmetric);
  const FullMatrix<double> consistent = consistent_tangent(element, state);
  EXPECT_EQ(f, force(element, state));
  double largest = 0, skew = 0;
  for (unsigned int i = 0; i < shell_dofs; ++i)
    for (unsigned int j = 0; j < shell_dofs; ++j)
    {
      largest = std::max(largest, std::abs(consistent(i, j)));
      skew    = std::max(skew, std::abs(consistent(i, j) - consistent(j, i)));
    }
  for (unsigned int i = 0; i < shell_dofs; ++i)
    for (unsigned int j = 0; j < shell_dofs; ++j)
    {
      EXPECT_NEAR(symmetric(i, j), 0.5 * (consistent(i, j) + consistent(j, i)),
                  1e-14 * largest);
      EXPECT_EQ(symmetric(i, j), symmetric(j, i));
    }
  EXPECT_GT(skew, 1e-8 * largest); // a deformed state: there was a skew part
}

// The linearization the kernel returns is d and J = dd/dp under the
// perturbation of 'perturbed': d(p) - (d + J p) is of second order in p,
// at a state with rotations above 90 degrees.
TEST(CorotationalShell, LinearizationIsTheDofsAndTheirJacobian)
{
  const CorotationalShell   element(initial_triangle, thick_material(),
                                    with_bending(both_elements[0]));
  const State               state = random_deformed_state(initial_triangle, 7);
  FullMatrix<double>        tangent;
  ShellDisplacements        f;
  CorotationalLinearization linearization;
  element.internal_force(state.x, state.rotations,
                         CorotationalTangent::consistent, f, &tangent, nullptr,
                         &linearization);
  EXPECT_EQ(linearization.dofs,
            element.deformational_dofs(state.x, state.rotations));
  std::array<double, 2> remainders;
  for (unsigned int k = 0; k < 2; ++k)
  {
    const double step  = k == 0 ? 1e-3 : 5e-4;
    double       worst = 0;
    for (unsigned int b = 0; b < shell_dofs; ++b)
    {
      const State moved = perturbed(state, b, step);
      const auto  d     = element.deformational_dofs(moved.x, moved.rotations);
      for (unsigned int a = 0; a < shell_dofs; ++a)
        worst = std::max(worst, std::abs(d[a] - linearization.dofs[a] -
                                         linearization.jacobian[a][b] * step));
    }
    remainders[k] = worst;
  }
  EXPECT_GT(remainders[1], 0);
  EXPECT_NEAR(remainders[0] / remainders[1], 4.0, 0.2);
}

// Geometric terms from given deformational DOFs: with the state's own d the
// tangent is bit for bit the consistent one; with others only the tangent
// changes, by K_l times the difference through the geometric terms.
TEST(CorotationalShell, GeometricDofsChangeOnlyTheGeometricTerms)
{
  const CorotationalShell  element(initial_triangle, thick_material(),
                                   with_bending(both_elements[0]));
  const State              state = random_deformed_state(initial_triangle, 9);
  const FullMatrix<double> consistent = consistent_tangent(element, state);
  const ShellDisplacements own =
      element.deformational_dofs(state.x, state.rotations);
  FullMatrix<double> same, other;
  ShellDisplacements f_same, f_other;
  element.internal_force(state.x, state.rotations,
                         CorotationalTangent::consistent, f_same, &same, &own);
  EXPECT_EQ(relative_difference(same, consistent), 0);
  EXPECT_EQ(f_same, force(element, state));

  ShellDisplacements zero{};
  element.internal_force(state.x, state.rotations,
                         CorotationalTangent::consistent, f_other, &other,
                         &zero);
  EXPECT_EQ(f_other, force(element, state));
  // With zero local forces only J^T K_l J is left: the symmetric material
  // part, against which the consistent tangent of a deformed state differs.
  for (unsigned int i = 0; i < shell_dofs; ++i)
    for (unsigned int j = 0; j < shell_dofs; ++j)
      EXPECT_NEAR(other(i, j), other(j, i), 1e-12 * other.frobenius_norm());
  EXPECT_GT(relative_difference(other, consistent), 1e-6);
}

// The SE(3) exponential's translation part V(theta) = int_0^1 exp(s
// skew(theta)) ds, by Gauss-Legendre quadrature (independent of the closed
// form), for small, medium and near-2pi angles; and V V^-1 = I.
TEST(LieGroups, LeftJacobianIsTheAverageRotation)
{
  const double nodes[5]   = {-0.9061798459386640, -0.5384693101056831, 0,
                             0.5384693101056831, 0.9061798459386640};
  const double weights[5] = {0.2369268850561891, 0.4786286704993665,
                             0.5688888888888889, 0.4786286704993665,
                             0.2369268850561891};
  const dealii::Tensor<1, 3> axis({0.48, -0.6, 0.64});
  for (const double angle : {1e-5, 5e-4, 0.52, 2.0, 5.5})
  {
    // Composite rule on 20 panels: exact to about 1e-15 for these angles.
    dealii::Tensor<2, 3> average;
    const unsigned int   panels = 20;
    for (unsigned int p = 0; p < panels; ++p)
      for (unsigned int k = 0; k < 5; ++k)
      {
        const double s = (p + 0.5 * (1 + nodes[k])) / panels;
        average += (0.5 * weights[k] / panels) * rotation_exp(s * angle * axis);
      }
    const dealii::Tensor<2, 3> V = so3_left_jacobian(angle * axis);
    const dealii::Tensor<2, 3> product =
        V * so3_left_jacobian_inverse(angle * axis);
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
      {
        EXPECT_NEAR(V[i][j], average[i][j], 1e-13) << "angle " << angle;
        EXPECT_NEAR(product[i][j], i == j ? 1 : 0, 1e-12) << "angle " << angle;
      }
  }
}
