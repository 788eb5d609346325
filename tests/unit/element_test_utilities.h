#pragma once

// Small independent tools for the element unit tests: eigenvalues,
// rotations, rigid-body modes and a patch-test driver.

#include <coshell/element/shell_element.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/lapack_full_matrix.h>
#include <deal.II/lac/vector.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

namespace coshell::element::testing
{
  using dealii::FullMatrix;
  using dealii::Vector;

  /// ||K - K^T||_F / ||K||_F.
  /// A generic (scalene, acute-free) triangle and material shared by the
  /// kernel tests.
  inline const PlanarTriangle generic_planar_triangle = {
      {Point<2>(0.2, -0.1), Point<2>(1.3, 0.25), Point<2>(0.45, 0.9)}};

  inline ShellMaterial test_material()
  {
    ShellMaterial material;
    material.youngs_modulus = 7.0e4;
    material.poisson_ratio  = 0.33;
    material.thickness      = 0.05;
    return material;
  }

  /// Checks that a 9x9 kernel (3 DoFs per node) gives the same matrix when
  /// vertices 1 and 2 are swapped (clockwise order), up to the renumbering.
  inline void expect_independent_of_orientation(
      const std::function<FullMatrix<double>(const PlanarTriangle &)> &kernel)
  {
    const PlanarTriangle clockwise = {{generic_planar_triangle[0],
                                       generic_planar_triangle[2],
                                       generic_planar_triangle[1]}};
    const auto           ccw       = kernel(generic_planar_triangle);
    const auto           cw        = kernel(clockwise);
    const unsigned int   vertex[3] = {0, 2, 1};
    for (unsigned int a = 0; a < 9; ++a)
      for (unsigned int b = 0; b < 9; ++b)
        EXPECT_NEAR(cw(a, b),
                    ccw(3 * vertex[a / 3] + a % 3, 3 * vertex[b / 3] + b % 3),
                    1e-12 * ccw.frobenius_norm());
  }

  inline double relative_asymmetry(const FullMatrix<double> &matrix)
  {
    FullMatrix<double> difference(matrix);
    difference.Tadd(-1.0, matrix);
    return difference.frobenius_norm() / matrix.frobenius_norm();
  }

  /// All eigenvalues of a symmetric matrix, ascending (LAPACK dsyevx).
  inline std::vector<double>
  symmetric_eigenvalues(const FullMatrix<double> &matrix)
  {
    const double bound = 2.0 * matrix.frobenius_norm() + 1.0;
    dealii::LAPACKFullMatrix<double> lapack(matrix.m(), matrix.n());
    lapack = matrix;
    Vector<double>     eigenvalues;
    FullMatrix<double> eigenvectors;
    lapack.compute_eigenvalues_symmetric(-bound, bound, 0.0, eigenvalues,
                                         eigenvectors);
    std::vector<double> sorted(eigenvalues.begin(), eigenvalues.end());
    std::sort(sorted.begin(), sorted.end());
    return sorted;
  }

  /// ||K r|| / (||K||_F ||r||): zero for a rigid-body mode r.
  inline double relative_residual(const FullMatrix<double> &matrix,
                                  const Vector<double>     &mode)
  {
    Vector<double> product(matrix.m());
    matrix.vmult(product, mode);
    return product.l2_norm() / (matrix.frobenius_norm() * mode.l2_norm());
  }

  /// Rotation by angle about axis (Rodrigues).
  inline Tensor<2, 3> rotation_matrix(Tensor<1, 3> axis, double angle)
  {
    axis /= axis.norm();
    Tensor<2, 3> rotation;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        rotation[i][j] = (i == j ? std::cos(angle) : 0.0) +
                         (1.0 - std::cos(angle)) * axis[i] * axis[j];
    rotation[0][1] -= std::sin(angle) * axis[2];
    rotation[0][2] += std::sin(angle) * axis[1];
    rotation[1][0] += std::sin(angle) * axis[2];
    rotation[1][2] -= std::sin(angle) * axis[0];
    rotation[2][0] -= std::sin(angle) * axis[1];
    rotation[2][1] += std::sin(angle) * axis[0];
    return rotation;
  }

  /// A fixed, arbitrary rotation used to tilt flat test geometry into 3D.
  inline Tensor<2, 3> tilt()
  {
    return rotation_matrix(Tensor<1, 3>({0.3, -0.7, 0.5}), 1.1);
  }

  /// Places a planar point into space: origin + R (x, y, 0).
  inline Point<3>
  embed(const Point<2> &p, const Tensor<2, 3> &rotation, const Point<3> &origin)
  {
    return origin + rotation * Tensor<1, 3>({p[0], p[1], 0.0});
  }

  /// The six rigid-body modes of the 18 shell DOFs: translations
  /// u = t and infinitesimal rotations u = omega x X, theta = omega.
  inline std::vector<Vector<double>>
  rigid_modes(const SpatialTriangle &triangle)
  {
    std::vector<Vector<double>> modes;
    for (unsigned int k = 0; k < 6; ++k)
    {
      Tensor<1, 3> unit;
      unit[k % 3] = 1.0;
      Vector<double> mode(shell_dofs);
      for (unsigned int v = 0; v < 3; ++v)
      {
        const Tensor<1, 3> translation =
            k < 3 ? unit : cross_product_3d(unit, triangle[v]);
        for (unsigned int a = 0; a < 3; ++a)
        {
          mode(6 * v + a)     = translation[a];
          mode(6 * v + 3 + a) = k < 3 ? 0.0 : unit[a];
        }
      }
      modes.push_back(mode);
    }
    return modes;
  }

  /// Linear in-plane field u = a + G x with the drilling rotation equal to
  /// the in-plane rotation (G_yx - G_xy) / 2; per node (u, v, theta_z).
  struct LinearInPlaneField
  {
    double u0 = 0.1, ux = 0.013, uy = -0.021;
    double v0 = -0.2, vx = 0.034, vy = 0.008;

    std::array<double, 3> at(const Point<2> &p) const
    {
      return {{u0 + ux * p[0] + uy * p[1], v0 + vx * p[0] + vy * p[1],
               0.5 * (vx - uy)}};
    }

    /// N = A [[1,nu,0],[nu,1,0],[0,0,(1-nu)/2]] (u_x, v_y, u_y + v_x).
    MembraneForces forces(const ShellMaterial &material) const
    {
      const double a  = material.membrane_rigidity();
      const double nu = material.poisson_ratio;
      return {{a * (ux + nu * vy), a * (nu * ux + vy),
               a * (1 - nu) / 2 * (uy + vx)}};
    }
  };

  /// w = w0 + wx x + wy y + a x^2 + b xy + c y^2 (constant curvature);
  /// per node (w, theta_x = w_y, theta_y = -w_x).
  struct QuadraticDeflection
  {
    double w0 = 0.05, wx = -0.03, wy = 0.02;
    double a = 0.3, b = -0.2, c = 0.45;

    std::array<double, 3> at(const Point<2> &p) const
    {
      const double x = p[0], y = p[1];
      return {{w0 + wx * x + wy * y + a * x * x + b * x * y + c * y * y,
               wy + b * x + 2 * c * y, -(wx + 2 * a * x + b * y)}};
    }

    /// kappa = (-w_xx, -w_yy, -2 w_xy).
    std::array<double, 3> curvature() const
    {
      return {{-2 * a, -2 * c, -2 * b}};
    }

    BendingMoments moments(const ShellMaterial &material) const
    {
      const double d     = material.bending_rigidity();
      const double nu    = material.poisson_ratio;
      const auto   kappa = curvature();
      return {{d * (kappa[0] + nu * kappa[1]), d * (nu * kappa[0] + kappa[1]),
               d * (1 - nu) / 2 * kappa[2]}};
    }

    /// Area density of the bending energy, 1/2 kappa . M.
    double energy_density(const ShellMaterial &material) const
    {
      const auto kappa = curvature();
      const auto m     = moments(material);
      return 0.5 * (kappa[0] * m[0] + kappa[1] * m[1] + kappa[2] * m[2]);
    }
  };

  /// Nodal values of a 3-component field at the vertices of a triangle.
  template<typename Field>
  std::array<double, 9> nodal_values(const PlanarTriangle &triangle,
                                     const Field          &field)
  {
    std::array<double, 9> dofs;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int c = 0; c < 3; ++c)
        dofs[3 * i + c] = field.at(triangle[i])[c];
    return dofs;
  }

  /// Triangles around one interior node, all counter-clockwise.
  struct Patch
  {
    std::vector<Point<2>>                    nodes;
    std::vector<std::array<unsigned int, 3>> triangles;
    std::vector<unsigned int>                interior_nodes;

    PlanarTriangle planar(unsigned int element) const
    {
      const auto &t = triangles[element];
      return {{nodes[t[0]], nodes[t[1]], nodes[t[2]]}};
    }
  };

  /// Five distorted triangles around the off-centre node 0. The vertex order
  /// of each triangle starts at a different node so that element frames
  /// differ from each other.
  inline Patch distorted_patch()
  {
    Patch patch;
    patch.nodes     = {Point<2>(0.47, 0.36), Point<2>(0.0, 0.0),
                       Point<2>(1.1, 0.12),  Point<2>(1.32, 0.93),
                       Point<2>(0.55, 1.21), Point<2>(-0.23, 0.68)};
    patch.triangles = {
        {{0, 1, 2}}, {{2, 3, 0}}, {{4, 0, 3}}, {{0, 4, 5}}, {{1, 0, 5}}};
    patch.interior_nodes = {0};
    return patch;
  }

  /// Nodal values of a 3-component field at every node of a patch.
  template<typename Field>
  Vector<double> patch_values(const Patch &patch, const Field &field)
  {
    Vector<double> values(3 * patch.nodes.size());
    for (unsigned int n = 0; n < patch.nodes.size(); ++n)
      for (unsigned int c = 0; c < 3; ++c)
        values(3 * n + c) = field.at(patch.nodes[n])[c];
    return values;
  }

  /// Assembles the patch, prescribes `exact` at every boundary node and
  /// returns the DOF vector with the interior DOFs solved for.
  inline Vector<double> solve_patch(
      const Patch                                           &patch,
      unsigned int                                           dofs_per_node,
      const std::function<FullMatrix<double>(unsigned int)> &element_stiffness,
      const Vector<double>                                  &exact)
  {
    const unsigned int n_dofs = patch.nodes.size() * dofs_per_node;
    FullMatrix<double> stiffness(n_dofs, n_dofs);
    for (unsigned int e = 0; e < patch.triangles.size(); ++e)
    {
      const FullMatrix<double> local = element_stiffness(e);
      for (unsigned int a = 0; a < local.m(); ++a)
        for (unsigned int b = 0; b < local.n(); ++b)
          stiffness(patch.triangles[e][a / dofs_per_node] * dofs_per_node +
                        a % dofs_per_node,
                    patch.triangles[e][b / dofs_per_node] * dofs_per_node +
                        b % dofs_per_node) += local(a, b);
    }

    std::vector<unsigned int> free;
    for (const unsigned int node : patch.interior_nodes)
      for (unsigned int c = 0; c < dofs_per_node; ++c)
        free.push_back(node * dofs_per_node + c);

    // K_ff x_f = -K_fb u_b, with u_b the exact boundary values.
    Vector<double> boundary = exact;
    for (const unsigned int i : free)
      boundary(i) = 0.0;
    Vector<double> load(n_dofs);
    stiffness.vmult(load, boundary);

    FullMatrix<double> free_matrix(free.size(), free.size());
    Vector<double>     free_load(free.size());
    for (unsigned int i = 0; i < free.size(); ++i)
    {
      free_load(i) = -load(free[i]);
      for (unsigned int j = 0; j < free.size(); ++j)
        free_matrix(i, j) = stiffness(free[i], free[j]);
    }
    free_matrix.gauss_jordan();
    Vector<double> free_solution(free.size());
    free_matrix.vmult(free_solution, free_load);

    Vector<double> solution = exact;
    for (unsigned int i = 0; i < free.size(); ++i)
      solution(free[i]) = free_solution(i);
    return solution;
  }

  /// Gathers the element DOFs of a patch-wide vector.
  template<unsigned int n>
  std::array<double, n> element_dofs(const Patch          &patch,
                                     unsigned int          element,
                                     const Vector<double> &all)
  {
    constexpr unsigned int per_node = n / 3;
    std::array<double, n>  dofs;
    for (unsigned int a = 0; a < n; ++a)
      dofs[a] =
          all(patch.triangles[element][a / per_node] * per_node + a % per_node);
    return dofs;
  }

  /// Maximum |a_i - b_i| over the given DOFs.
  inline double max_difference(const Vector<double> &a, const Vector<double> &b)
  {
    Vector<double> difference = a;
    difference -= b;
    return difference.linfty_norm();
  }
  /// Membrane constant-strain patch test on the distorted patch: the
  /// interior node must reproduce the linear field (u, v and theta_z = its
  /// rotation) and every element the exact constant membrane forces.
  template<typename Stiffness, typename Forces>
  void expect_membrane_patch_test(const Stiffness &stiffness,
                                  const Forces    &forces_of)
  {
    const Patch              patch    = distorted_patch();
    const ShellMaterial      material = test_material();
    const LinearInPlaneField field;
    const Vector<double>     exact    = patch_values(patch, field);
    const Vector<double>     solution = solve_patch(
            patch, 3,
            [&](unsigned int e) { return stiffness(patch.planar(e), material); },
            exact);
    EXPECT_LT(max_difference(solution, exact), 1e-13);
    const auto expected = field.forces(material);
    for (unsigned int e = 0; e < patch.triangles.size(); ++e)
    {
      const auto forces = forces_of(patch.planar(e), material,
                                    element_dofs<9>(patch, e, solution));
      for (unsigned int c = 0; c < 3; ++c)
        EXPECT_NEAR(forces[c], expected[c], 1e-10 * std::abs(expected[0]))
            << "element " << e << ", component " << c;
    }
  }
} // namespace coshell::element::testing
