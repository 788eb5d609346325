// The largest strains recovered from the stress resultants
// (model::largest_strains): exact for the fields the elements represent
// exactly, a uniform stretch and a uniform curvature.
#include <coshell/mesh/mesh.h>
#include <coshell/model/internal_force.h>
#include <coshell/model/shell_model.h>

#include <gtest/gtest.h>

namespace
{
  using namespace coshell;

  /// Plate [0, 2]^2, h = 0.1, E = 2, nu = 0.3, ANDES + DKT.
  struct StrainPlate
  {
    mesh::Surface surface;
    const bool    meshed =
        (mesh::make_rectangle(
             surface, 2, 2, 2, 2, mesh::TrianglePattern::crossed),
         true);
    const model::ShellModel model{surface, parameters(),
                                  dealii::Tensor<1, 3>({0, 0, 1})};

    static model::ElementParameters parameters()
    {
      model::ElementParameters element;
      element.material.thickness      = 0.1;
      element.material.youngs_modulus = 2;
      element.material.poisson_ratio  = 0.3;
      return element;
    }

    /// u = (a x, 0, k x^2 / 2) with the matching rotation about y.
    dealii::Vector<double> field(double stretch, double curvature) const
    {
      dealii::Vector<double> u(model.n_dofs());
      const auto            &vertices = surface.get_vertices();
      for (unsigned int v = 0; v < vertices.size(); ++v)
      {
        const double x    = vertices[v][0];
        const auto  &dofs = model.vertex_dofs(v);
        u[dofs[0]]        = stretch * x;
        u[dofs[2]]        = 0.5 * curvature * x * x;
        u[dofs[4]]        = -curvature * x; // theta_y = -dw/dx
      }
      return u;
    }
  };
} // namespace

TEST(LargestStrains, UniformStretchIsTheMembraneStrain)
{
  const StrainPlate plate;
  const auto        largest = model::largest_strains(
             plate.model, plate.model.resultants(plate.field(1e-3, 0)));
  EXPECT_NEAR(largest.membrane, 1e-3, 1e-12);
  EXPECT_NEAR(largest.bending, 0, 1e-12);
}

TEST(LargestStrains, UniformCurvatureGivesHalfThicknessTimesCurvature)
{
  const StrainPlate plate;
  const double      curvature = 0.02; // 1 / length
  const auto        largest   = model::largest_strains(
               plate.model, plate.model.resultants(plate.field(0, curvature)));
  EXPECT_NEAR(largest.bending, 0.5 * 0.1 * curvature, 1e-12);
  EXPECT_NEAR(largest.membrane, 0, 1e-12);
}
