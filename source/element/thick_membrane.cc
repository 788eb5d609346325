#include <coshell/element/thick_membrane.h>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace coshell::element
{
  namespace
  {
    // The density is a function of four variables: the in-plane metric
    // (g11, g22, g12) and the thickness stretch lambda, in this order.
    constexpr unsigned int n_variables = 4;
    using Gradient4                    = std::array<double, n_variables>;
    using Hessian4 = std::array<std::array<double, n_variables>, n_variables>;

    struct Metric
    {
      double g11, g22, g12;
      double determinant() const
      {
        return g11 * g22 - g12 * g12;
      }
    };

    // I1 = g11 + g22 + lambda^2 and J = lambda sqrt(det g), with their
    // first and second derivatives in (g11, g22, g12, lambda).
    struct Invariants
    {
      double    first, volume_ratio;
      Gradient4 d_first{}, d_volume{};
      Hessian4  dd_first{}, dd_volume{};
    };

    Invariants invariants(const Metric &g, double lambda)
    {
      const double det  = g.determinant();
      const double root = std::sqrt(det);
      Invariants   inv;
      inv.first          = g.g11 + g.g22 + lambda * lambda;
      inv.volume_ratio   = lambda * root;
      inv.d_first        = {1.0, 1.0, 0.0, 2.0 * lambda};
      inv.dd_first[3][3] = 2.0;

      const Gradient4 d_det = {g.g22, g.g11, -2.0 * g.g12, 0.0};
      Hessian4        dd_det{};
      dd_det[0][1] = dd_det[1][0] = 1.0;
      dd_det[2][2]                = -2.0;
      for (unsigned int p = 0; p < 3; ++p)
      {
        inv.d_volume[p] = lambda * d_det[p] / (2.0 * root);
        for (unsigned int q = 0; q < 3; ++q)
          inv.dd_volume[p][q] =
              lambda * (dd_det[p][q] / (2.0 * root) -
                        d_det[p] * d_det[q] / (4.0 * det * root));
        inv.dd_volume[p][3] = inv.dd_volume[3][p] = d_det[p] / (2.0 * root);
      }
      inv.d_volume[3] = root;
      return inv;
    }

    struct Density
    {
      double    value = 0.0;
      Gradient4 gradient{};
      Hessian4  hessian{};
    };

    // W(I1, J) and its derivatives chained through the invariants:
    // W_I = c10 J^{-2/3}, W_J = -2/3 c10 J^{-5/3} I1 + 2 (J - 1) / d1,
    // W_II = 0, W_IJ = -2/3 c10 J^{-5/3}, W_JJ = 10/9 c10 J^{-8/3} I1 + 2/d1.
    Density density(const NeoHookeanLaw &law, const Metric &g, double lambda)
    {
      const Invariants inv = invariants(g, lambda);
      const double     J   = inv.volume_ratio;
      const double     I1  = inv.first;
      const double     j23 = std::pow(J, -2.0 / 3.0);
      const double     w_i = law.c10 * j23;
      const double     w_j =
          -2.0 / 3.0 * law.c10 * j23 / J * I1 + 2.0 * (J - 1.0) / law.d1;
      const double w_ij = -2.0 / 3.0 * law.c10 * j23 / J;
      const double w_jj =
          10.0 / 9.0 * law.c10 * j23 / (J * J) * I1 + 2.0 / law.d1;

      Density d;
      d.value = law.energy_density(I1, J);
      for (unsigned int p = 0; p < n_variables; ++p)
      {
        d.gradient[p] = w_i * inv.d_first[p] + w_j * inv.d_volume[p];
        for (unsigned int q = 0; q < n_variables; ++q)
          d.hessian[p][q] = w_ij * (inv.d_first[p] * inv.d_volume[q] +
                                    inv.d_volume[p] * inv.d_first[q]) +
                            w_jj * inv.d_volume[p] * inv.d_volume[q] +
                            w_i * inv.dd_first[p][q] +
                            w_j * inv.dd_volume[p][q];
      }
      return d;
    }

    // F's columns F_1 = sum_a x_a dN_a/dX_1 and F_2 likewise.
    std::array<Tensor<1, 3>, 2>
    deformation_columns(const SpatialTriangle             &positions,
                        const std::array<Tensor<1, 2>, 3> &shape_gradients)
    {
      std::array<Tensor<1, 3>, 2> columns;
      for (unsigned int a = 0; a < 3; ++a)
        for (unsigned int alpha = 0; alpha < 2; ++alpha)
          columns[alpha] += shape_gradients[a][alpha] * positions[a];
      return columns;
    }

    Metric metric(const std::array<Tensor<1, 3>, 2> &F)
    {
      return {F[0] * F[0], F[1] * F[1], F[0] * F[1]};
    }

    // d g_p / d x_{a,i} for the metric entries p = (g11, g22, g12):
    // 2 N_a,1 F_1, 2 N_a,2 F_2 and N_a,1 F_2 + N_a,2 F_1.
    std::array<std::array<double, 9>, 3>
    metric_gradients(const std::array<Tensor<1, 3>, 2> &F,
                     const std::array<Tensor<1, 2>, 3> &dN)
    {
      std::array<std::array<double, 9>, 3> dg{};
      for (unsigned int a = 0; a < 3; ++a)
        for (unsigned int i = 0; i < 3; ++i)
        {
          dg[0][3 * a + i] = 2.0 * dN[a][0] * F[0][i];
          dg[1][3 * a + i] = 2.0 * dN[a][1] * F[1][i];
          dg[2][3 * a + i] = dN[a][0] * F[1][i] + dN[a][1] * F[0][i];
        }
      return dg;
    }

    // d^2 g_p / d x_{a,i} d x_{b,j} = delta_ij M_p(a, b).
    double metric_curvature(unsigned int                       p,
                            const std::array<Tensor<1, 2>, 3> &dN,
                            unsigned int                       a,
                            unsigned int                       b)
    {
      if (p < 2)
        return 2.0 * dN[a][p] * dN[b][p];
      return dN[a][0] * dN[b][1] + dN[a][1] * dN[b][0];
    }

    bool admissible(const Metric &g, const std::array<double, 3> &stretches)
    {
      for (const double lambda : stretches)
        if (!(lambda > 0.0))
          return false;
      return g.determinant() > 0.0;
    }
  } // namespace

  NeoHookeanLaw NeoHookeanLaw::from_material(const ShellMaterial &material)
  {
    material.validate();
    const double E  = material.youngs_modulus;
    const double nu = material.poisson_ratio;
    return {E / (4.0 * (1.0 + nu)), 6.0 * (1.0 - 2.0 * nu) / E};
  }

  double NeoHookeanLaw::energy_density(double first_invariant,
                                       double volume_ratio) const
  {
    if (!(volume_ratio > 0.0))
      return std::numeric_limits<double>::infinity();
    return c10 * (std::pow(volume_ratio, -2.0 / 3.0) * first_invariant - 3.0) +
           (volume_ratio - 1.0) * (volume_ratio - 1.0) / d1;
  }

  ThickMembrane::ThickMembrane(const PlanarTriangle &reference,
                               double                reference_thickness,
                               const NeoHookeanLaw  &law)
      : shape_gradients_(barycentric_gradients(reference)),
        area_(std::abs(signed_area(reference))),
        thickness_(reference_thickness), law_(law)
  {
    if (!(reference_thickness > 0.0))
      throw std::invalid_argument(
          "ThickMembrane: the reference thickness must be positive");
  }

  double ThickMembrane::energy(const SpatialTriangle       &positions,
                               const std::array<double, 3> &stretches) const
  {
    const Metric g = metric(deformation_columns(positions, shape_gradients_));
    if (!admissible(g, stretches))
      return std::numeric_limits<double>::infinity();
    double sum = 0.0;
    for (const double lambda : stretches)
      sum += density(law_, g, lambda).value;
    return area_ * thickness_ / 3.0 * sum;
  }

  void ThickMembrane::derivatives(const SpatialTriangle       &positions,
                                  const std::array<double, 3> &stretches,
                                  dealii::Vector<double>      &gradient,
                                  dealii::FullMatrix<double>  &hessian) const
  {
    const auto   F = deformation_columns(positions, shape_gradients_);
    const Metric g = metric(F);
    if (!admissible(g, stretches))
      throw std::domain_error("ThickMembrane: a vertex thickness stretch or "
                              "the in-plane area ratio is not positive");
    const auto  &dN     = shape_gradients_;
    const auto   dg     = metric_gradients(F, dN);
    const double weight = area_ * thickness_ / 3.0;
    gradient.reinit(thick_membrane_dofs);
    hessian.reinit(thick_membrane_dofs, thick_membrane_dofs);

    // The metric is shared by the three vertex points, so its derivatives
    // are summed over them before the chain rule to positions.
    Gradient4 w_g{};
    Hessian4  w_gg{};
    for (unsigned int v = 0; v < 3; ++v)
    {
      const Density      d            = density(law_, g, stretches[v]);
      const unsigned int lambda_dof   = 9 + v;
      gradient(lambda_dof)            = weight * d.gradient[3];
      hessian(lambda_dof, lambda_dof) = weight * d.hessian[3][3];
      for (unsigned int p = 0; p < 3; ++p)
      {
        w_g[p] += weight * d.gradient[p];
        for (unsigned int q = 0; q < 3; ++q)
          w_gg[p][q] += weight * d.hessian[p][q];
        for (unsigned int k = 0; k < 9; ++k)
        {
          const double coupling = weight * d.hessian[p][3] * dg[p][k];
          hessian(k, lambda_dof) += coupling;
          hessian(lambda_dof, k) += coupling;
        }
      }
    }

    for (unsigned int k = 0; k < 9; ++k)
    {
      for (unsigned int p = 0; p < 3; ++p)
        gradient(k) += w_g[p] * dg[p][k];
      for (unsigned int l = 0; l < 9; ++l)
      {
        double value = 0.0;
        for (unsigned int p = 0; p < 3; ++p)
          for (unsigned int q = 0; q < 3; ++q)
            value += w_gg[p][q] * dg[p][k] * dg[q][l];
        if (k % 3 == l % 3)
          for (unsigned int p = 0; p < 3; ++p)
            value += w_g[p] * metric_curvature(p, dN, k / 3, l / 3);
        hessian(k, l) = value;
      }
    }
  }
} // namespace coshell::element
