// The strains recovered from the stress resultants (model::cell_strains,
// model::largest_strains): exact for the fields the elements represent
// exactly, a uniform stretch and a uniform curvature, alone and together.
#include <coshell/mesh/mesh.h>
#include <coshell/model/internal_force.h>
#include <coshell/model/shell_model.h>

#include <gtest/gtest.h>

#include <algorithm>

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

    /// u = (a x, 0, k x^2 / 2) with the matching rotation about y, or
    /// with 'across' the curvature about x instead: w = k y^2 / 2.
    dealii::Vector<double>
    field(double stretch, double curvature, bool across = false) const
    {
      dealii::Vector<double> u(model.n_dofs());
      const auto            &vertices = surface.get_vertices();
      for (unsigned int v = 0; v < vertices.size(); ++v)
      {
        const double x = vertices[v][0], y = vertices[v][1];
        const auto  &dofs = model.vertex_dofs(v);
        u[dofs[0]]        = stretch * x;
        if (across)
        {
          u[dofs[2]] = 0.5 * curvature * y * y;
          u[dofs[3]] = curvature * y; // theta_x = dw/dy
        }
        else
        {
          u[dofs[2]] = 0.5 * curvature * x * x;
          u[dofs[4]] = -curvature * x; // theta_y = -dw/dx
        }
      }
      return u;
    }

    /// Every cell's strains of the field u.
    std::vector<model::CellStrains>
    strains(const dealii::Vector<double> &u) const
    {
      const auto                      resultants = model.resultants(u);
      std::vector<model::CellStrains> cells;
      for (const auto &cell : model.dof_handler().active_cell_iterators())
        cells.push_back(model::cell_strains(
            model.material(cell), resultants[cell->active_cell_index()]));
      return cells;
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
  EXPECT_NEAR(largest.surface, 1e-3, 1e-12);
}

TEST(LargestStrains, UniformCurvatureGivesHalfThicknessTimesCurvature)
{
  const StrainPlate plate;
  const double      curvature = 0.02; // 1 / length
  const auto        largest   = model::largest_strains(
               plate.model, plate.model.resultants(plate.field(0, curvature)));
  EXPECT_NEAR(largest.bending, 0.5 * 0.1 * curvature, 1e-12);
  EXPECT_NEAR(largest.membrane, 0, 1e-12);
  EXPECT_NEAR(largest.surface, 0.5 * 0.1 * curvature, 1e-12);
}

// Stretch and curvature along the same axis: the surfaces' strains are
// a -+ h k / 2, so the larger in magnitude is their sum, in every cell.
TEST(CellStrains, AlignedStretchAndCurvatureAddAtTheSurface)
{
  const StrainPlate plate;
  const double      stretch = 1e-3, curvature = 0.02, half = 0.05;
  for (const auto &cell : plate.strains(plate.field(stretch, curvature)))
  {
    EXPECT_NEAR(cell.membrane, stretch, 1e-12);
    EXPECT_NEAR(cell.bending, half * curvature, 1e-12);
    EXPECT_NEAR(cell.surface, stretch + half * curvature, 1e-12);
  }
}

// Stretch along x, curvature along y: the surface tensor is
// diag(a, +-h k / 2), so its largest principal value is the larger of the
// two, not their sum: the surface strain is a tensor sum.
TEST(CellStrains, CrossedStretchAndCurvatureDoNotAdd)
{
  const StrainPlate plate;
  const double      stretch = 1e-3, curvature = 0.03, half = 0.05;
  for (const auto &cell :
       plate.strains(plate.field(stretch, curvature, /*across=*/true)))
  {
    EXPECT_NEAR(cell.membrane, stretch, 1e-12);
    EXPECT_NEAR(cell.bending, half * curvature, 1e-12);
    EXPECT_NEAR(cell.surface, std::max(stretch, half * curvature), 1e-12);
  }
}

// The kernel alone, with Poisson's ratio in play: a pure in-plane shear
// force N_xy gives principal strains +-(1 + nu) N_xy / (E h); a twisting
// moment M_xy gives +-6 (1 + nu) M_xy / (E h^2) at the surfaces.
TEST(CellStrains, ShearAndTwistThroughPoissonsRatio)
{
  coshell::element::ShellMaterial material;
  material.youngs_modulus = 3;
  material.poisson_ratio  = 0.4;
  material.thickness      = 0.2;
  coshell::element::ShellResultants resultants;
  resultants.membrane_local = {0, 0, 0.05};
  resultants.bending_local  = {0, 0, 0.001};
  const auto   strains = coshell::model::cell_strains(material, resultants);
  const double shear   = 1.4 * 0.05 / (3 * 0.2);
  const double twist   = 6 * 1.4 * 0.001 / (3 * 0.04);
  EXPECT_NEAR(strains.membrane, shear, 1e-14);
  EXPECT_NEAR(strains.bending, twist, 1e-14);
  EXPECT_NEAR(strains.surface, shear + twist, 1e-14);
}
