// ShellProblem's bound on the rotation of one Newton correction
// (Nonlinear solver/Largest rotation per correction): the fraction it
// admits is the bound over the largest vertex rotation, translations never
// limit it, and without a bound every correction passes whole.

#include <coshell/mesh/mesh.h>
#include <coshell/model/shell_problem.h>

#include <gtest/gtest.h>

using namespace coshell;

namespace
{
  /// A 2 x 2 crossed plate with no contributions and no constraints.
  struct BarePlate
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
    model::ShellProblem               problem{model, state, constraints, {}};

    static dealii::AffineConstraints<double> closed()
    {
      dealii::AffineConstraints<double> constraints;
      constraints.close();
      return constraints;
    }
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
