// Discrete Kirchhoff Triangle (Batoz, Bathe & Ho 1980), built from its
// definition rather than from the tabulated explicit form (Batoz 1982):
// the normal rotations beta = (beta_x, beta_y) = (-w_x, -w_y) are
// quadratic over the triangle, and the Kirchhoff hypothesis is imposed
// at the vertices and edge midpoints, which eliminates the midside
// rotations in favour of the 9 vertex DOFs (w, theta_x, theta_y).
// Curvatures kappa = (beta_x,x, beta_y,y, beta_x,y + beta_y,x)
// = (-w_xx, -w_yy, -2 w_xy) are then linear.
//
// This file also holds what both bending elements share: the exact
// edge-midpoint integration and the dispatch on BendingElement.

#include <coshell/element/bending.h>

#include <deal.II/lac/vector.h>

#include <cmath>
#include <stdexcept>

namespace coshell::element
{
  namespace
  {
    constexpr unsigned int bending_dofs = 9;

    // Rows (beta_x, beta_y) over the bending DOFs at a vertex; the
    // Kirchhoff normal gives beta_x = theta_y and beta_y = -theta_x.
    FullMatrix<double> vertex_rotations(unsigned int vertex)
    {
      FullMatrix<double> beta(2, bending_dofs);
      beta(0, 3 * vertex + 2) = 1.0;
      beta(1, 3 * vertex + 1) = -1.0;
      return beta;
    }

    // Kirchhoff constraints at the midpoint of edge i-j. With w cubic
    // along the edge, w_s(mid) = 3 (w_j - w_i) / (2 l) - (w_s,i + w_s,j) / 4
    // and beta_s = -w_s; the normal rotation beta_n is taken linear.
    FullMatrix<double> midside_rotations(const PlanarTriangle &triangle,
                                         unsigned int          i,
                                         unsigned int          j)
    {
      const Tensor<1, 2> edge    = triangle[j] - triangle[i];
      const double       length  = edge.norm();
      const Tensor<1, 2> tangent = edge / length;
      const Tensor<1, 2> normal({-tangent[1], tangent[0]});

      FullMatrix<double> end_sum = vertex_rotations(i);
      end_sum.add(1.0, vertex_rotations(j));

      // beta = n (n . sum)/2 - s (s . sum)/4 + 3/(2l) (w_i - w_j) s
      FullMatrix<double> projector(2, 2);
      for (unsigned int a = 0; a < 2; ++a)
        for (unsigned int b = 0; b < 2; ++b)
          projector(a, b) =
              0.5 * normal[a] * normal[b] - 0.25 * tangent[a] * tangent[b];

      FullMatrix<double> beta(2, bending_dofs);
      projector.mmult(beta, end_sum);
      for (unsigned int a = 0; a < 2; ++a)
      {
        beta(a, 3 * i) += 1.5 / length * tangent[a];
        beta(a, 3 * j) -= 1.5 / length * tangent[a];
      }
      return beta;
    }

    // Quadratic rotation field: six nodes, vertices 0-2 then the midpoints
    // of edges (0,1), (1,2), (2,0).
    struct DktRotationField
    {
      explicit DktRotationField(const PlanarTriangle &triangle)
          : gradients(barycentric_gradients(triangle)),
            centroid((triangle[0] + triangle[1] + triangle[2]) / 3.0)
      {
        for (unsigned int i = 0; i < 3; ++i)
        {
          nodal[i]     = vertex_rotations(i);
          nodal[3 + i] = midside_rotations(triangle, i, (i + 1) % 3);
        }
      }

      // Cartesian gradients of the six quadratic shape functions at p.
      std::array<Tensor<1, 2>, 6> shape_gradients(const Point<2> &p) const
      {
        std::array<double, 3> L;
        for (unsigned int i = 0; i < 3; ++i)
          L[i] = 1.0 / 3.0 + gradients[i] * (p - centroid);

        std::array<Tensor<1, 2>, 6> result;
        for (unsigned int i = 0; i < 3; ++i)
        {
          const unsigned int j = (i + 1) % 3;
          result[i]            = (4.0 * L[i] - 1.0) * gradients[i];
          result[3 + i] = 4.0 * (L[j] * gradients[i] + L[i] * gradients[j]);
        }
        return result;
      }

      FullMatrix<double> curvatures(const Point<2> &p) const
      {
        const auto         shape = shape_gradients(p);
        FullMatrix<double> kappa(3, bending_dofs);
        for (unsigned int n = 0; n < 6; ++n)
          for (unsigned int d = 0; d < bending_dofs; ++d)
          {
            const double beta_x = nodal[n](0, d);
            const double beta_y = nodal[n](1, d);
            kappa(0, d) += shape[n][0] * beta_x;
            kappa(1, d) += shape[n][1] * beta_y;
            kappa(2, d) += shape[n][1] * beta_x + shape[n][0] * beta_y;
          }
        return kappa;
      }

      std::array<Tensor<1, 2>, 3>       gradients;
      Point<2>                          centroid;
      std::array<FullMatrix<double>, 6> nodal;
    };

    std::vector<FullMatrix<double>>
    curvature_matrices(BendingElement               type,
                       const PlanarTriangle        &triangle,
                       const std::vector<Point<2>> &points)
    {
      switch (type)
      {
      case BendingElement::dkt:
        return dkt_curvature_matrices(triangle, points);
      case BendingElement::przemieniecki:
        return przemieniecki_curvature_matrices(triangle, points);
      }
      throw std::invalid_argument("unknown bending element type");
    }

    FullMatrix<double> bending_material(const ShellMaterial &material)
    {
      return plane_stress_matrix(material.bending_rigidity(),
                                 material.poisson_ratio);
    }
  } // namespace

  std::vector<FullMatrix<double>>
  dkt_curvature_matrices(const PlanarTriangle        &triangle,
                         const std::vector<Point<2>> &points)
  {
    const DktRotationField          field(triangle);
    std::vector<FullMatrix<double>> result;
    result.reserve(points.size());
    for (const Point<2> &p : points)
      result.push_back(field.curvatures(p));
    return result;
  }

  FullMatrix<double> dkt_stiffness(const PlanarTriangle &triangle,
                                   const ShellMaterial  &material)
  {
    return bending_stiffness(BendingElement::dkt, triangle, material);
  }

  FullMatrix<double> bending_stiffness(BendingElement        type,
                                       const PlanarTriangle &triangle,
                                       const ShellMaterial  &material)
  {
    // Curvatures are linear, so kappa^T D kappa is quadratic and the
    // edge-midpoint rule (weight A/3 each) integrates it exactly; it is
    // also the rule the paper prescribes for its element.
    const std::vector<Point<2>> midpoints = {(triangle[0] + triangle[1]) / 2.0,
                                             (triangle[1] + triangle[2]) / 2.0,
                                             (triangle[2] + triangle[0]) / 2.0};
    const auto         kappas = curvature_matrices(type, triangle, midpoints);
    const double       weight = std::abs(signed_area(triangle)) / 3.0;
    const auto         moduli = bending_material(material);
    FullMatrix<double> stiffness(bending_dofs, bending_dofs);
    for (const auto &kappa : kappas)
      stiffness.triple_product(moduli, kappa, kappa, true, false, weight);
    return stiffness;
  }

  BendingMoments bending_moments(BendingElement              type,
                                 const PlanarTriangle       &triangle,
                                 const ShellMaterial        &material,
                                 const BendingDisplacements &dofs)
  {
    const Point<2> centroid = (triangle[0] + triangle[1] + triangle[2]) / 3.0;
    const FullMatrix<double> kappa_matrix =
        curvature_matrices(type, triangle, {centroid})[0];

    const dealii::Vector<double> displacements(dofs.begin(), dofs.end());
    dealii::Vector<double>       kappa(3), moments(3);
    kappa_matrix.vmult(kappa, displacements);
    bending_material(material).vmult(moments, kappa);
    return {{moments(0), moments(1), moments(2)}};
  }
} // namespace coshell::element
