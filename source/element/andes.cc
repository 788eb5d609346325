// The optimal ANDES membrane triangle with corner drilling freedoms:
// C. A. Felippa (2003), A study of optimal membrane triangles with drilling
// freedoms, CMAME 192:2125-2168, built on the template of Felippa &
// Militello (1992) and Alvin, de la Fuente, Haugen & Felippa (1992).
//
// K = K_b + K_h. The basic part K_b carries the constant strain states and
// alone decides the patch test; the higher-order part K_h only acts on the
// hierarchical rotations theta_i - theta_0, which every linear field with
// theta_i = its rotation makes zero, and its strains have zero mean over
// the element (energy orthogonality), so it never spoils the patch test.

#include <coshell/element/membrane.h>

#include <deal.II/lac/vector.h>

#include <algorithm>
#include <cmath>

namespace coshell::element
{
  namespace
  {
    using dealii::Vector;

    constexpr unsigned int membrane_dofs = 9;

    // The optimal instance of the ANDES template (Felippa 2003, Sec. 5): a
    // rectangle of two triangles stores the exact energy in in-plane pure
    // bending, for any aspect ratio.
    constexpr double                basic_drilling_weight = 1.5; // alpha_b
    constexpr std::array<double, 9> corner_strain_weights = {
        {1, 2, 1, 0, 1, -1, -1, -1, -2}}; // beta_1 .. beta_9

    // beta_0 = (1 - 4 nu^2)/2 makes that hold for any nu; it vanishes
    // at nu = 1/2, so it is floored to keep K_h (and the rank) alive.
    double higher_order_weight(double poisson_ratio)
    {
      return std::max(0.5 * (1.0 - 4.0 * poisson_ratio * poisson_ratio), 0.01);
    }

    // Normalisation of K_h = c beta_0 T^T K_theta T for K_theta as built
    // below (Q_c = (2A/3) beta / l^2, integrated exactly). It is fixed by
    // the optimality condition itself: in pure bending of a rectangular
    // unit K_b stores 3/4 of the exact energy (alpha_b = 3/2) and K_theta
    // 2/9 of it, for every aspect ratio and nu = 0, so beta_0 = 1/2 needs
    // c = 9/4 (test Andes.PureBendingOfRectangularUnitsIsExact, which also
    // checks nu = 0.3, where beta_0 = 0.32).
    constexpr double higher_order_normalisation = 9.0 / 4.0;

    FullMatrix<double> membrane_material(const ShellMaterial &material)
    {
      return plane_stress_matrix(material.membrane_rigidity(),
                                 material.poisson_ratio);
    }

    constexpr unsigned int dof(unsigned int vertex, unsigned int component)
    {
      return 3 * vertex + component;
    }

    constexpr unsigned int next(unsigned int vertex)
    {
      return (vertex + 1) % 3;
    }

    // Edge e runs from vertex e to vertex e+1: Felippa's sides 12, 23, 31,
    // counter-clockwise, so (dy, -dx) is the outward normal times length.
    Tensor<1, 2> edge(const PlanarTriangle &triangle, unsigned int e)
    {
      return triangle[next(e)] - triangle[e];
    }

    // The template is written for counter-clockwise vertices; a clockwise
    // triangle is handled by swapping vertices 1 and 2 there and back.
    std::array<unsigned int, 3> counter_clockwise_order(const PlanarTriangle &t)
    {
      barycentric_gradients(t); // throws DegenerateTriangle, like the CST
      if (signed_area(t) > 0.0)
        return {{0, 1, 2}};
      return {{0, 2, 1}};
    }

    PlanarTriangle reordered(const PlanarTriangle              &triangle,
                             const std::array<unsigned int, 3> &order)
    {
      return {{triangle[order[0]], triangle[order[1]], triangle[order[2]]}};
    }

    // Membrane DOF a of the reordered triangle is DOF original_dof(a) of
    // the triangle as given.
    unsigned int original_dof(unsigned int                       a,
                              const std::array<unsigned int, 3> &order)
    {
      return dof(order[a / 3], a % 3);
    }

    // Lumping matrix L (9x3, per unit thickness): nodal forces and drilling
    // moments f = L N of a constant stress resultant N = (Nxx, Nyy, Nxy)
    // acting on the element boundary. Along each edge the displacement is
    // linear plus an outward Allman bubble, alpha_b (l/8) (theta_j -
    // theta_i) at the midpoint; its work against the constant traction
    // gives the drilling rows +-alpha_b l^2 N_nn / 12.
    FullMatrix<double> lumping_matrix(const PlanarTriangle &triangle,
                                      double                drilling_scale)
    {
      FullMatrix<double> lumping(membrane_dofs, 3);
      for (unsigned int e = 0; e < 3; ++e)
      {
        const double dx = edge(triangle, e)[0], dy = edge(triangle, e)[1];
        // Half of the edge traction l N n = N (dy, -dx) goes to each end.
        for (const unsigned int v : {e, next(e)})
        {
          lumping(dof(v, 0), 0) += 0.5 * dy;
          lumping(dof(v, 0), 2) -= 0.5 * dx;
          lumping(dof(v, 1), 1) -= 0.5 * dx;
          lumping(dof(v, 1), 2) += 0.5 * dy;
        }
        // l^2 N_nn = Nxx dy^2 + Nyy dx^2 - 2 Nxy dx dy.
        const double bubble_work[3] = {dy * dy, dx * dx, -2.0 * dx * dy};
        for (unsigned int c = 0; c < 3; ++c)
        {
          const double moment =
              drilling_scale * basic_drilling_weight * bubble_work[c] / 12.0;
          lumping(dof(next(e), 2), c) += moment;
          lumping(dof(e, 2), c) -= moment;
        }
      }
      return lumping;
    }

    // Basic (constant) strain L^T u / A: the mean strain over the element.
    Vector<double> basic_strain(const PlanarTriangle        &triangle,
                                const MembraneDisplacements &dofs,
                                double                       drilling_scale)
    {
      Vector<double> strain(3);
      lumping_matrix(triangle, drilling_scale)
          .Tvmult(strain, Vector<double>(dofs.begin(), dofs.end()));
      strain /= signed_area(triangle);
      return strain;
    }

    FullMatrix<double> basic_stiffness(const PlanarTriangle &triangle,
                                       const ShellMaterial  &material,
                                       double                drilling_scale)
    {
      const FullMatrix<double> lumping =
          lumping_matrix(triangle, drilling_scale);
      FullMatrix<double> stiffness(membrane_dofs, membrane_dofs);
      stiffness.triple_product(membrane_material(material), lumping, lumping,
                               false, true, 1.0 / signed_area(triangle));
      return stiffness;
    }

    // T (3x9): hierarchical rotations theta_i - theta_0, where theta_0 =
    // (1/2A) int (v_x - u_y)/2 dA = (1/4A) sum_edges (u_i + u_j) dx +
    // (v_i + v_j) dy (Green) is the rotation of the linear displacements.
    FullMatrix<double> hierarchical_rotations(const PlanarTriangle &triangle)
    {
      const double   scale = 1.0 / (4.0 * signed_area(triangle));
      Vector<double> mean_rotation(membrane_dofs);
      for (unsigned int e = 0; e < 3; ++e)
        for (const unsigned int v : {e, next(e)})
        {
          mean_rotation(dof(v, 0)) += scale * edge(triangle, e)[0];
          mean_rotation(dof(v, 1)) += scale * edge(triangle, e)[1];
        }
      FullMatrix<double> rotations(3, membrane_dofs);
      for (unsigned int i = 0; i < 3; ++i)
      {
        for (unsigned int a = 0; a < membrane_dofs; ++a)
          rotations(i, a) = -mean_rotation(a);
        rotations(i, dof(i, 2)) += 1.0;
      }
      return rotations;
    }

    // Natural strains are the extensions along the three edge directions,
    // eps_e = (dx^2 eps_xx + dy^2 eps_yy + dx dy gamma_xy) / l^2; this
    // returns the inverse map T_e: natural -> (eps_xx, eps_yy, gamma_xy).
    FullMatrix<double> natural_to_cartesian(const PlanarTriangle &triangle)
    {
      FullMatrix<double> to_natural(3, 3);
      for (unsigned int e = 0; e < 3; ++e)
      {
        const Tensor<1, 2> d       = edge(triangle, e);
        const double       length2 = d.norm_square();
        to_natural(e, 0)           = d[0] * d[0] / length2;
        to_natural(e, 1)           = d[1] * d[1] / length2;
        to_natural(e, 2)           = d[0] * d[1] / length2;
      }
      FullMatrix<double> to_cartesian(3, 3);
      to_cartesian.invert(to_natural);
      return to_cartesian;
    }

    // Q_c (3x3): natural strains at corner c from the hierarchical
    // rotations, (2A/3) beta_k / l_e^2. Felippa's Q_1 holds beta_1..9 row
    // by row (edges 12, 23, 31; rotations 1, 2, 3); Q_2 and Q_3 are its
    // cyclic relabellings, which makes the element vertex-order invariant.
    FullMatrix<double> corner_natural_strains(const PlanarTriangle &triangle,
                                              unsigned int          corner)
    {
      const double       scale = 2.0 * signed_area(triangle) / 3.0;
      FullMatrix<double> strains(3, 3);
      for (unsigned int e = 0; e < 3; ++e)
        for (unsigned int i = 0; i < 3; ++i)
        {
          const unsigned int row    = (e + 3 - corner) % 3;
          const unsigned int column = (i + 3 - corner) % 3;
          strains(e, i) = scale * corner_strain_weights[3 * row + column] /
                          edge(triangle, e).norm_square();
        }
      return strains;
    }

    // K_theta = int B^T E_nat B dA with the natural strains linear between
    // the corners, integrated exactly by the three edge-midpoint rule.
    FullMatrix<double> hierarchical_stiffness(const PlanarTriangle &triangle,
                                              const ShellMaterial  &material)
    {
      const FullMatrix<double> to_cartesian = natural_to_cartesian(triangle);
      FullMatrix<double>       natural_rigidity(3, 3);
      natural_rigidity.triple_product(membrane_material(material), to_cartesian,
                                      to_cartesian, true, false);

      std::array<FullMatrix<double>, 3> corners;
      for (unsigned int c = 0; c < 3; ++c)
        corners[c] = corner_natural_strains(triangle, c);

      FullMatrix<double> stiffness(3, 3);
      for (unsigned int c = 0; c < 3; ++c)
      {
        FullMatrix<double> midpoint(corners[c]);
        midpoint.add(1.0, corners[next(c)]);
        stiffness.triple_product(natural_rigidity, midpoint, midpoint, true,
                                 false, signed_area(triangle) / 12.0);
      }
      return stiffness;
    }

    FullMatrix<double> higher_order_stiffness(const PlanarTriangle &triangle,
                                              const ShellMaterial  &material)
    {
      const FullMatrix<double> rotations = hierarchical_rotations(triangle);
      FullMatrix<double>       stiffness(membrane_dofs, membrane_dofs);
      stiffness.triple_product(hierarchical_stiffness(triangle, material),
                               rotations, rotations, true, false,
                               higher_order_normalisation *
                                   higher_order_weight(material.poisson_ratio));
      return stiffness;
    }
  } // namespace

  FullMatrix<double> andes_stiffness(const PlanarTriangle &triangle,
                                     const ShellMaterial  &material,
                                     const AndesScales    &scales)
  {
    const auto           order = counter_clockwise_order(triangle);
    const PlanarTriangle ccw   = reordered(triangle, order);
    FullMatrix<double>   ccw_stiffness =
        basic_stiffness(ccw, material, scales.basic_drilling);
    ccw_stiffness.add(scales.higher_order,
                      higher_order_stiffness(ccw, material));

    FullMatrix<double> stiffness(membrane_dofs, membrane_dofs);
    for (unsigned int a = 0; a < membrane_dofs; ++a)
      for (unsigned int b = 0; b < membrane_dofs; ++b)
        stiffness(original_dof(a, order), original_dof(b, order)) =
            ccw_stiffness(a, b);
    return stiffness;
  }

  MembraneForces andes_membrane_forces(const PlanarTriangle        &triangle,
                                       const ShellMaterial         &material,
                                       const MembraneDisplacements &dofs,
                                       const AndesScales           &scales)
  {
    const auto            order = counter_clockwise_order(triangle);
    MembraneDisplacements ccw_dofs;
    for (unsigned int a = 0; a < membrane_dofs; ++a)
      ccw_dofs[a] = dofs[original_dof(a, order)];

    Vector<double> forces(3);
    membrane_material(material).vmult(
        forces, basic_strain(reordered(triangle, order), ccw_dofs,
                             scales.basic_drilling));
    return {{forces(0), forces(1), forces(2)}};
  }
} // namespace coshell::element
