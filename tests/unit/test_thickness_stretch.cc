// The thickness-stretch shell in the model (Element/Thickness stretch):
// the stretch DoFs after the FESystem's, and the residual of the internal
// force, the thick membrane with its bending at the current thickness and
// the face pressure against central differences of ShellProblem::energy()
// over every DoF; the stretch columns of the tangent against central
// differences of the residual.

#include <coshell/base/tangent_matrix.h>
#include <coshell/mesh/mesh.h>
#include <coshell/model/internal_force.h>
#include <coshell/model/shell_problem.h>
#include <coshell/model/thickness_stretch.h>

#include <deal.II/lac/full_matrix.h>

#include <cmath>

#include <gtest/gtest.h>

using namespace coshell;

namespace
{
  model::ElementParameters stretch_parameters()
  {
    model::ElementParameters element;
    element.material.youngs_modulus   = 1.0;
    element.material.poisson_ratio    = 0.42;
    element.material.thickness        = 0.3;
    element.formulation               = model::Formulation::corotational;
    element.thickness_stretch         = true;
    element.options.membrane_in_plane = false;
    return element;
  }

  /// A 2 x 2 crossed plate of the lens's material with thickness
  /// stretches, its internal force, thick membrane and a face pressure,
  /// deformed on every DoF (stretches by up to 0.1).
  struct StretchPlate
  {
    mesh::Surface surface;
    const bool    meshed =
        (mesh::make_rectangle(
             surface, 2, 2, 2, 2, mesh::TrianglePattern::crossed),
         true);
    const model::ShellModel           model{surface, stretch_parameters(),
                                  dealii::Tensor<1, 3>({0, 0, 1})};
    model::ShellState                 state{model, true};
    dealii::AffineConstraints<double> constraints = closed();
    model::ShellProblem problem{model, state, constraints, ingredients()};
    base::TangentMatrix tangent;

    StretchPlate()
    {
      problem.reinit_tangent(tangent);
      dealii::Vector<double> deformation(model.n_dofs());
      for (unsigned int k = 0; k < deformation.size(); ++k)
        deformation[k] = 0.1 * std::sin(1.7 * (k + 1));
      problem.apply_increment(deformation);
      problem.save();
    }

    static dealii::AffineConstraints<double> closed()
    {
      dealii::AffineConstraints<double> constraints;
      constraints.close();
      return constraints;
    }

    std::vector<std::unique_ptr<model::Contribution>> ingredients() const
    {
      std::vector<std::unique_ptr<model::Contribution>> list;
      list.push_back(std::make_unique<model::InternalForce>(
          model, model::Formulation::corotational,
          element::CorotationalTangent::consistent, false, false));
      list.push_back(std::make_unique<model::ThickMembraneForce>(model));
      list.push_back(std::make_unique<model::FacePressure>(model, 0.05));
      return list;
    }

    /// Residual (and energy) after 'increment', then back.
    dealii::Vector<double> residual_after(const dealii::Vector<double> &inc,
                                          double *energy = nullptr)
    {
      problem.apply_increment(inc);
      dealii::Vector<double> residual(inc.size());
      problem.evaluate(residual, nullptr);
      if (energy)
        *energy = problem.energy();
      problem.restore();
      return residual;
    }

    dealii::Vector<double> unit(unsigned int k, double size) const
    {
      dealii::Vector<double> increment(model.n_dofs());
      increment[k] = size;
      return increment;
    }
  };
} // namespace

TEST(ThicknessStretch, OneStretchDofPerVertexAfterTheFESystem)
{
  StretchPlate plate;
  // 2 x 2 crossed: 9 corners and 4 centres.
  EXPECT_EQ(plate.model.n_dofs(), plate.model.n_fe_dofs() + 13);
  for (unsigned int v = 0; v < plate.surface.n_vertices(); ++v)
    EXPECT_GE(plate.model.thickness_dof(v), plate.model.n_fe_dofs());
}

TEST(ThicknessStretch, ResidualIsMinusTheEnergyGradient)
{
  StretchPlate plate;
  double       energy   = 0;
  const auto   residual = plate.residual_after(plate.unit(0, 0), &energy);
  ASSERT_TRUE(std::isfinite(energy));
  const double step = 1e-6, scale = residual.linfty_norm();
  ASSERT_GT(scale, 0);
  for (unsigned int k = 0; k < plate.model.n_dofs(); ++k)
  {
    double above = 0, below = 0;
    plate.residual_after(plate.unit(k, step), &above);
    plate.residual_after(plate.unit(k, -step), &below);
    EXPECT_NEAR((above - below) / (2 * step), -residual[k], 1e-6 * scale)
        << "DoF " << k;
  }
}

TEST(ThicknessStretch, StretchColumnsOfTheTangentAreExact)
{
  StretchPlate           plate;
  dealii::Vector<double> residual(plate.model.n_dofs());
  plate.tangent.zero();
  plate.problem.evaluate(residual, &plate.tangent);
  dealii::FullMatrix<double> tangent;
  tangent.copy_from(plate.tangent.serial());
  const double step    = 1e-6;
  double       largest = 0, mismatch = 0;
  for (auto k = plate.model.n_fe_dofs(); k < plate.model.n_dofs(); ++k)
  {
    dealii::Vector<double> column = plate.residual_after(plate.unit(k, -step));
    column -= plate.residual_after(plate.unit(k, step));
    column /= 2 * step; // -dr/dlambda_k = K e_k
    for (unsigned int i = 0; i < plate.model.n_dofs(); ++i)
    {
      largest  = std::max(largest, std::abs(tangent(i, k)));
      mismatch = std::max(mismatch, std::abs(column[i] - tangent(i, k)));
      // ... and the stretch rows equal the columns (a symmetric block).
      EXPECT_NEAR(tangent(k, i), tangent(i, k), 1e-12 * largest);
    }
  }
  ASSERT_GT(largest, 0);
  EXPECT_LT(mismatch, 1e-6 * largest);
}
