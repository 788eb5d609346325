// ShellProblem's bound on the rotation of one Newton correction
// (Nonlinear solver/Largest rotation per correction): the fraction it
// admits is the bound over the largest vertex rotation, translations never
// limit it, and without a bound every correction passes whole.
//
// The co-rotational internal force with extrapolated forces in its
// geometric stiffness (Nonlinear solver/Geometric stiffness): the same
// residual, a tangent within O(|dp|^2) of the exact one after a correction
// dp, and the exact tangent again after restore().
//
// The shell's mass (ShellModel::mass), which summary.json reports.
//
// The co-rotational internal force as a potential: the residual against
// finite differences of the strain energy, the tangent against finite
// differences of the residual; with dead loads added, the residual against
// finite differences of the problem's energy (ShellProblem::energy()), and
// no energy where a point moment acts on finite rotations.

#include <coshell/mesh/mesh.h>
#include <coshell/model/external_loads.h>
#include <coshell/model/internal_force.h>
#include <coshell/model/loads.h>
#include <coshell/model/shell_problem.h>

#include <deal.II/lac/full_matrix.h>

#include <cmath>
#include <sstream>

#include <gtest/gtest.h>

using namespace coshell;

namespace
{
  /// A 2 x 2 crossed plate, its model and state, and no constraints.
  struct PlateMesh
  {
    mesh::Surface surface;
    // Members are built in order: the mesh before the model on it.
    const bool meshed =
        (mesh::make_rectangle(
             surface, 2, 2, 2, 2, mesh::TrianglePattern::crossed),
         true);
    const model::ShellModel           model{surface, model::ElementParameters(),
                                  dealii::Tensor<1, 3>({0, 0, 1})};
    model::ShellState                 state{model, true};
    dealii::AffineConstraints<double> constraints = closed();

    static dealii::AffineConstraints<double> closed()
    {
      dealii::AffineConstraints<double> constraints;
      constraints.close();
      return constraints;
    }
  };

  /// The plate with no contributions.
  struct BarePlate : PlateMesh
  {
    model::ShellProblem problem{model, state, constraints, {}};
  };
} // namespace

TEST(ShellProblem, BoundsTheLargestRotationOfACorrection)
{
  BarePlate                plate;
  const auto              &model = plate.model;
  dealii::Vector<double>   correction(model.n_dofs());
  const model::VertexDofs &turned = model.vertex_dofs(4);
  // A 0.5 rad turn of one vertex, 0.05 rad of another, and a translation
  // of 10 (length) that no rotation bound may limit.
  correction[turned[model::rx]]               = 0.3;
  correction[turned[model::rz]]               = 0.4;
  correction[model.vertex_dofs(1)[model::ry]] = 0.05;
  correction[model.vertex_dofs(2)[model::uz]] = 10;
  EXPECT_EQ(plate.problem.admissible_fraction(correction), 1);

  plate.problem.set_correction_limits({0.1});
  EXPECT_NEAR(plate.problem.admissible_fraction(correction), 0.2, 1e-15);
  plate.problem.set_correction_limits({0.5});
  EXPECT_EQ(plate.problem.admissible_fraction(correction), 1);

  correction[turned[model::rx]] = 0;
  correction[turned[model::rz]] = 0;
  plate.problem.set_correction_limits({0.01});
  EXPECT_NEAR(plate.problem.admissible_fraction(correction), 0.2, 1e-15);
}

namespace
{
  /// The plate whose one contribution is the co-rotational internal
  /// force, deformed by a pattern of up to 0.1 (rad and length units, the
  /// plate being 2 x 2) on every DoF and evaluated there; step() moves it
  /// on along another pattern.
  struct ElasticPlate : PlateMesh
  {
    model::ShellProblem    problem;
    base::TangentMatrix    tangent;
    dealii::Vector<double> residual;

    explicit ElasticPlate(bool extrapolated, bool exact_after_failure = false)
        : problem(model,
                  state,
                  constraints,
                  internal_force(extrapolated, exact_after_failure))
    {
      problem.reinit_tangent(tangent);
      residual.reinit(model.n_dofs());
      problem.apply_increment(pattern(0.1, 1.7));
      problem.save();
      evaluate();
    }

    std::vector<std::unique_ptr<model::Contribution>>
    internal_force(bool extrapolated, bool exact_after_failure) const
    {
      std::vector<std::unique_ptr<model::Contribution>> contributions;
      contributions.push_back(std::make_unique<model::InternalForce>(
          model, model::Formulation::corotational,
          element::CorotationalTangent::consistent, extrapolated,
          exact_after_failure));
      return contributions;
    }

    dealii::Vector<double> pattern(double size, double frequency) const
    {
      dealii::Vector<double> v(model.n_dofs());
      for (unsigned int k = 0; k < v.size(); ++k)
        v[k] = size * std::sin(frequency * (k + 1));
      return v;
    }

    dealii::FullMatrix<double> evaluate()
    {
      tangent.zero();
      problem.evaluate(residual, &tangent);
      dealii::FullMatrix<double> full;
      full.copy_from(tangent.serial());
      return full;
    }

    dealii::FullMatrix<double> step(double size)
    {
      problem.apply_increment(pattern(size, 2.3));
      return evaluate();
    }
  };

  double difference(const dealii::FullMatrix<double> &a,
                    dealii::FullMatrix<double>        b)
  {
    b.add(-1.0, a);
    return b.frobenius_norm() / a.frobenius_norm();
  }
} // namespace

TEST(InternalForce, ExtrapolatedForcesTangentIsExactToSecondOrder)
{
  const std::array<double, 2> sizes = {{0.002, 0.001}};
  std::array<double, 2>       differences;
  for (unsigned int i = 0; i < 2; ++i)
  {
    const double size = sizes[i];
    ElasticPlate exact(false), extrapolated(true);
    const auto   exact_tangent = exact.step(size);
    const auto   tangent       = extrapolated.step(size);
    // The force is the exact one either way.
    dealii::Vector<double> residual_difference = extrapolated.residual;
    residual_difference -= exact.residual;
    EXPECT_EQ(residual_difference.linfty_norm(), 0);
    differences[i] = difference(exact_tangent, tangent);
    // The same configuration again: the same extrapolation, not the
    // exact tangent.
    EXPECT_EQ(difference(tangent, extrapolated.evaluate()), 0);
  }
  // Not the exact tangent, but off by O(|dp|^2): a mismatch of the
  // rotation convention between J and dp would leave O(|dp|).
  EXPECT_GT(differences[1], 1e-8);
  EXPECT_NEAR(differences[0] / differences[1], 4.0, 0.2);
}

TEST(InternalForce, ExtrapolationIsForgottenOnRestore)
{
  ElasticPlate exact(false), extrapolated(true);
  extrapolated.step(0.01);
  extrapolated.problem.restore();
  EXPECT_EQ(difference(exact.evaluate(), extrapolated.evaluate()), 0);
}

// restore() is what a failed step does: with Geometric stiffness = auto
// the rest of the stage then takes the exact tangent, also at
// configurations the extrapolation would reach; explicitly extrapolated
// forces stay extrapolated.
TEST(InternalForce, AFailedStepLeavesTheStageOnTheExactTangent)
{
  ElasticPlate exact(false), automatic(true, true), extrapolated(true);
  for (ElasticPlate *plate : {&automatic, &extrapolated})
  {
    plate->step(0.01);
    plate->problem.restore();
    plate->problem.save(); // a step converges after the cut
  }
  for (const double size : {0.002, 0.001})
  {
    const auto exact_tangent = exact.step(size);
    EXPECT_EQ(difference(exact_tangent, automatic.step(size)), 0);
    const auto tangent = extrapolated.step(size);
    if (size == 0.001) // the second configuration: extrapolated
    {
      EXPECT_GT(difference(exact_tangent, tangent), 1e-10);
    }
  }
}

// A symmetric tangent assembled below its diagonal only, for CHOLMOD
// (coshell::base::TangentMatrix::set_lower_only), is the whole one's lower
// triangle to the bit, with the same residual, and mirrored it is the whole
// tangent.
TEST(ShellProblem, AssemblesTheLowerTriangleAloneToTheBit)
{
  PlateMesh                                         plate;
  std::vector<std::unique_ptr<model::Contribution>> contributions;
  contributions.push_back(std::make_unique<model::InternalForce>(
      plate.model, model::Formulation::corotational,
      element::CorotationalTangent::symmetric, false, false));
  model::ShellProblem problem(plate.model, plate.state, plate.constraints,
                              std::move(contributions));
  ASSERT_TRUE(problem.symmetric_tangent());
  dealii::Vector<double> deformation(plate.model.n_dofs());
  for (unsigned int k = 0; k < deformation.size(); ++k)
    deformation[k] = 0.1 * std::sin(1.7 * (k + 1));
  problem.apply_increment(deformation);
  base::TangentMatrix whole, lower;
  problem.reinit_tangent(whole);
  problem.reinit_tangent(lower);
  lower.set_lower_only(true);
  dealii::Vector<double> whole_residual(deformation.size()),
      lower_residual(deformation.size());
  whole.zero();
  problem.evaluate(whole_residual, &whole);
  lower.zero();
  problem.evaluate(lower_residual, &lower);
  for (unsigned int k = 0; k < deformation.size(); ++k)
    ASSERT_EQ(lower_residual[k], whole_residual[k]) << "residual " << k;
  const auto &matrix = whole.serial();
  for (unsigned int i = 0; i < matrix.m(); ++i)
    for (auto e = matrix.begin(i); e != matrix.end(i); ++e)
      ASSERT_EQ(lower.serial().el(i, e->column()),
                e->column() <= i ? e->value() : 0.0)
          << "entry (" << i << ", " << e->column() << ")";
  lower.mirror_lower();
  for (unsigned int i = 0; i < matrix.m(); ++i)
    for (auto e = matrix.begin(i); e != matrix.end(i); ++e)
      ASSERT_EQ(lower.serial().el(i, e->column()), e->value())
          << "entry (" << i << ", " << e->column() << "), mirrored";
}

TEST(ShellModel, MassIntegratesDensityTimesALinearThickness)
{
  // [0, 2]^2 with density 3 and thickness 0.1 + 0.05 x, evaluated at each
  // triangle's centroid, which integrates a linear field exactly:
  // 3 (0.1 * 4 + 0.05 * int x dA) = 3 (0.4 + 0.05 * 4) = 1.8.
  mesh::Surface surface;
  mesh::make_rectangle(surface, 2, 2, 3, 2, mesh::TrianglePattern::crossed);
  model::ElementParameters parameters;
  parameters.material.density     = 3;
  parameters.thickness_expression = "0.1 + 0.05 * x";
  const model::ShellModel graded{surface, parameters,
                                 dealii::Tensor<1, 3>({0, 0, 1})};
  EXPECT_NEAR(graded.mass(), 1.8, 1e-13);
  parameters.thickness_expression = "";
  parameters.material.thickness   = 0.1;
  const model::ShellModel uniform{surface, parameters,
                                  dealii::Tensor<1, 3>({0, 0, 1})};
  EXPECT_NEAR(uniform.mass(), 3 * 0.1 * 4, 1e-13);
  parameters.material.density = 0;
  const model::ShellModel massless{surface, parameters,
                                   dealii::Tensor<1, 3>({0, 0, 1})};
  EXPECT_EQ(massless.mass(), 0);
}

// The co-rotational shell as a potential, seen through the whole problem
// (ShellProblem with the internal force alone, the plate deformed by up to
// 0.1 on every DoF, away from equilibrium): its residual is minus the
// gradient of the strain energy, and its consistent tangent the
// derivative of minus the residual, both against central differences
// through the problem's own increment map (translations added, rotations
// composed), which is the map Newton and a line search on the energy use.
namespace
{
  /// A unit increment of DoF k, times 'size'.
  dealii::Vector<double>
  unit_increment(unsigned int n, unsigned int k, double size)
  {
    dealii::Vector<double> increment(n);
    increment[k] = size;
    return increment;
  }

  /// The strain energy after 'increment', then back to the saved state.
  double energy_after(ElasticPlate &plate, const dealii::Vector<double> &inc)
  {
    plate.problem.apply_increment(inc);
    const double energy =
        plate.problem.find<model::InternalForce>()->strain_energy(plate.state);
    plate.problem.restore();
    return energy;
  }

  /// The residual after 'increment', then back to the saved state.
  dealii::Vector<double> residual_after(ElasticPlate                 &plate,
                                        const dealii::Vector<double> &inc)
  {
    plate.problem.apply_increment(inc);
    dealii::Vector<double> residual(inc.size());
    plate.problem.evaluate(residual, nullptr);
    plate.problem.restore();
    return residual;
  }
} // namespace

TEST(InternalForce, ResidualIsMinusTheStrainEnergyGradient)
{
  ElasticPlate       plate(false);
  const unsigned int n     = plate.model.n_dofs();
  const double       step  = 1e-6;
  const double       scale = plate.residual.linfty_norm();
  ASSERT_GT(scale, 0);
  for (unsigned int k = 0; k < n; ++k)
  {
    const double slope = (energy_after(plate, unit_increment(n, k, step)) -
                          energy_after(plate, unit_increment(n, k, -step))) /
                         (2 * step);
    EXPECT_NEAR(slope, -plate.residual[k], 1e-6 * scale) << "DoF " << k;
  }
}

TEST(InternalForce, ConsistentTangentIsTheDerivativeOfTheGradient)
{
  ElasticPlate                     plate(false);
  const dealii::FullMatrix<double> tangent = plate.evaluate();
  const unsigned int               n       = plate.model.n_dofs();
  const double                     step    = 1e-6;
  double                           largest = 0, mismatch = 0;
  for (unsigned int k = 0; k < n; ++k)
  {
    dealii::Vector<double> column =
        residual_after(plate, unit_increment(n, k, -step));
    column -= residual_after(plate, unit_increment(n, k, step));
    column /= 2 * step; // -dr/dx_k = K e_k
    for (unsigned int i = 0; i < n; ++i)
    {
      largest  = std::max(largest, std::abs(tangent(i, k)));
      mismatch = std::max(mismatch, std::abs(column[i] - tangent(i, k)));
    }
  }
  ASSERT_GT(largest, 0);
  EXPECT_LT(mismatch, 1e-6 * largest);
}

// The whole problem as a potential: the co-rotational shell under dead
// loads (pressure, gravity and a point force), its residual against central
// differences of ShellProblem::energy() over every DoF, through the
// problem's increment map; a point moment on finite rotations has no
// potential, and the problem then has no energy.
namespace
{
  /// Loads from the given entries of subsection Loads.
  model::Loads
  loads_of(const std::vector<std::pair<std::string, std::string>> &entries)
  {
    dealii::ParameterHandler prm;
    model::Loads::declare_parameters(prm);
    prm.enter_subsection("Loads");
    for (const auto &[name, value] : entries)
      prm.set(name, value);
    prm.leave_subsection();
    model::Loads loads;
    loads.parse_parameters(prm);
    return loads;
  }

  struct LoadedPlate : PlateMesh
  {
    std::ostringstream  log;
    model::ShellProblem problem;

    explicit LoadedPlate(const model::Loads &loads)
        : problem(model, state, constraints, contributions(loads))
    {
    }

    std::vector<std::unique_ptr<model::Contribution>>
    contributions(const model::Loads &loads)
    {
      std::vector<std::unique_ptr<model::Contribution>> list;
      list.push_back(std::make_unique<model::InternalForce>(
          model, model::Formulation::corotational,
          element::CorotationalTangent::consistent, false, false));
      list.push_back(
          std::make_unique<model::ExternalLoads>(model, loads, true, log));
      return list;
    }

    /// The energy after 'increment', evaluated there, then back.
    double energy_after(const dealii::Vector<double> &increment)
    {
      problem.apply_increment(increment);
      dealii::Vector<double> residual(increment.size());
      problem.evaluate(residual, nullptr);
      const double energy = problem.energy();
      problem.restore();
      return energy;
    }
  };
} // namespace

TEST(ShellProblem, ResidualIsMinusTheEnergyGradientUnderDeadLoads)
{
  LoadedPlate            plate(loads_of({{"Pressure", "0.3"},
                                         {"Gravity", "0.1, -0.2, 0.5"},
                                         {"Point forces", "1 1 0 : 0.2 0.1 -0.4"}}));
  const unsigned int     n = plate.model.n_dofs();
  dealii::Vector<double> deformation(n);
  for (unsigned int k = 0; k < n; ++k)
    deformation[k] = 0.1 * std::sin(1.7 * (k + 1));
  plate.problem.apply_increment(deformation);
  plate.problem.save();
  dealii::Vector<double> residual(n);
  plate.problem.evaluate(residual, nullptr);
  ASSERT_TRUE(std::isfinite(plate.problem.energy()));
  const double step = 1e-6, scale = residual.linfty_norm();
  ASSERT_GT(scale, 0);
  for (unsigned int k = 0; k < n; ++k)
  {
    const double slope = (plate.energy_after(unit_increment(n, k, step)) -
                          plate.energy_after(unit_increment(n, k, -step))) /
                         (2 * step);
    EXPECT_NEAR(slope, -residual[k], 1e-6 * scale) << "DoF " << k;
  }
}

TEST(ShellProblem, APointMomentOnFiniteRotationsHasNoEnergy)
{
  LoadedPlate plate(loads_of({{"Point moments", "1 1 0 : 0 0.1 0"}}));
  dealii::Vector<double> residual(plate.model.n_dofs());
  plate.problem.evaluate(residual, nullptr);
  EXPECT_TRUE(std::isnan(plate.problem.energy()));
}
