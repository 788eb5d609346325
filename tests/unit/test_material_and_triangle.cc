#include <coshell/element/material.h>
#include <coshell/element/triangle.h>

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

using namespace coshell::element;

namespace
{
  ShellMaterial steel_like()
  {
    ShellMaterial material;
    material.youngs_modulus = 2.1e11;
    material.poisson_ratio  = 0.3;
    material.thickness      = 0.01;
    material.density        = 7800.0;
    return material;
  }

  // Runs validate() and returns the message of the expected exception.
  std::string rejection_message(const ShellMaterial &material)
  {
    try
    {
      material.validate();
    }
    catch (const std::invalid_argument &error)
    {
      return error.what();
    }
    ADD_FAILURE() << "validate() accepted an invalid material";
    return {};
  }
} // namespace

TEST(Material, AcceptsTypicalValues)
{
  EXPECT_NO_THROW(steel_like().validate());
  ShellMaterial auxetic = steel_like();
  auxetic.poisson_ratio = -0.9;
  EXPECT_NO_THROW(auxetic.validate());
}

TEST(Material, RejectsNonPositiveYoungsModulus)
{
  for (const double e : {0.0, -1.0, std::nan("")})
  {
    ShellMaterial material  = steel_like();
    material.youngs_modulus = e;
    EXPECT_NE(rejection_message(material).find("Young's modulus"),
              std::string::npos);
  }
}

TEST(Material, RejectsNonPositiveThickness)
{
  for (const double h : {0.0, -0.01})
  {
    ShellMaterial material = steel_like();
    material.thickness     = h;
    EXPECT_NE(rejection_message(material).find("thickness"), std::string::npos);
  }
}

TEST(Material, RejectsPoissonRatioOutsideOpenInterval)
{
  for (const double nu : {-1.0, -1.5, 0.5, 0.6})
  {
    ShellMaterial material = steel_like();
    material.poisson_ratio = nu;
    EXPECT_NE(rejection_message(material).find("Poisson's ratio"),
              std::string::npos);
  }
  ShellMaterial material = steel_like();
  material.poisson_ratio = 0.6;
  EXPECT_EQ(rejection_message(material),
            "Poisson's ratio = 0.6 is outside (-1, 0.5)");
}

TEST(Material, RejectsNegativeDensity)
{
  ShellMaterial material = steel_like();
  material.density       = -1.0;
  EXPECT_NE(rejection_message(material).find("density"), std::string::npos);
}

TEST(Material, RigiditiesMatchClosedForms)
{
  ShellMaterial material;
  material.youngs_modulus = 3.0;
  material.poisson_ratio  = 0.25;
  material.thickness      = 0.2;
  // 1 - nu^2 = 15/16.
  EXPECT_DOUBLE_EQ(material.membrane_rigidity(), 3.0 * 0.2 * 16.0 / 15.0);
  EXPECT_DOUBLE_EQ(material.bending_rigidity(),
                   3.0 * 0.008 / 12.0 * 16.0 / 15.0);
  EXPECT_DOUBLE_EQ(material.shear_modulus(), 3.0 / 2.5);
}

TEST(Material, PlaneStressMatrixEntries)
{
  const auto matrix = plane_stress_matrix(2.0, 0.25);
  EXPECT_DOUBLE_EQ(matrix(0, 0), 2.0);
  EXPECT_DOUBLE_EQ(matrix(1, 1), 2.0);
  EXPECT_DOUBLE_EQ(matrix(0, 1), 0.5);
  EXPECT_DOUBLE_EQ(matrix(1, 0), 0.5);
  EXPECT_DOUBLE_EQ(matrix(2, 2), 0.75);
  EXPECT_DOUBLE_EQ(matrix(0, 2), 0.0);
  EXPECT_DOUBLE_EQ(matrix(2, 1), 0.0);
}

TEST(Triangle, SignedAreaFollowsOrientation)
{
  const PlanarTriangle ccw = {{Point<2>(0, 0), Point<2>(2, 0), Point<2>(0, 3)}};
  const PlanarTriangle cw  = {{ccw[0], ccw[2], ccw[1]}};
  EXPECT_DOUBLE_EQ(signed_area(ccw), 3.0);
  EXPECT_DOUBLE_EQ(signed_area(cw), -3.0);
  const SpatialTriangle spatial = {
      {Point<3>(1, 1, 1), Point<3>(1, 3, 1), Point<3>(1, 1, 4)}};
  EXPECT_DOUBLE_EQ(area(spatial), 3.0);
}

TEST(Triangle, BarycentricGradientsReproduceLinearFunctions)
{
  const PlanarTriangle triangle = {
      {Point<2>(0.3, -0.2), Point<2>(1.4, 0.5), Point<2>(-0.1, 1.3)}};
  const auto gradients = barycentric_gradients(triangle);
  // L_i(p_j) - L_i(p_i) = grad L_i . (p_j - p_i) = -1 for j != i.
  for (unsigned int i = 0; i < 3; ++i)
    for (unsigned int j = 0; j < 3; ++j)
    {
      if (i != j)
      {
        EXPECT_NEAR(gradients[i] * (triangle[j] - triangle[i]), -1.0, 1e-14);
      }
    }
  EXPECT_NEAR((gradients[0] + gradients[1] + gradients[2]).norm(), 0.0, 1e-14);
}

TEST(Triangle, ElementFrameIsOrthonormalAndPreservesShape)
{
  const SpatialTriangle triangle = {{Point<3>(0.1, 0.2, 0.3),
                                     Point<3>(1.0, -0.4, 0.8),
                                     Point<3>(0.2, 1.1, -0.5)}};
  const ElementFrame    frame    = make_element_frame(triangle);
  for (unsigned int a = 0; a < 3; ++a)
    for (unsigned int b = 0; b < 3; ++b)
      EXPECT_NEAR(frame.axes[a] * frame.axes[b], a == b ? 1.0 : 0.0, 1e-14);
  // Right-handed: (e1 x e2) . e3 = 1.
  EXPECT_NEAR(cross_product_3d(frame.axes[0], frame.axes[1]) * frame.axes[2],
              1.0, 1e-14);

  const Tensor<1, 3> edge01 = triangle[1] - triangle[0];
  EXPECT_NEAR((frame.axes[0] - edge01 / edge01.norm()).norm(), 0.0, 1e-14);
  EXPECT_NEAR(frame.planar[0].norm(), 0.0, 1e-14);
  EXPECT_NEAR(frame.planar[1][1], 0.0, 1e-14);
  EXPECT_GT(signed_area(frame.planar), 0.0);
  EXPECT_NEAR(signed_area(frame.planar), area(triangle), 1e-14);
  for (unsigned int i = 0; i < 3; ++i)
    for (unsigned int j = 0; j < 3; ++j)
      EXPECT_NEAR(frame.planar[i].distance(frame.planar[j]),
                  triangle[i].distance(triangle[j]), 1e-14);

  const Tensor<1, 3> local = to_local(frame, frame.axes[1] * 2.0);
  EXPECT_NEAR(local[0], 0.0, 1e-14);
  EXPECT_NEAR(local[1], 2.0, 1e-14);
  EXPECT_NEAR(local[2], 0.0, 1e-14);
}

TEST(Triangle, CollinearPointsAreDegenerate)
{
  const SpatialTriangle collinear = {
      {Point<3>(0, 0, 0), Point<3>(1, 1, 1), Point<3>(3, 3, 3)}};
  EXPECT_THROW(make_element_frame(collinear), DegenerateTriangle);
  const SpatialTriangle coincident = {
      {Point<3>(1, 2, 3), Point<3>(1, 2, 3), Point<3>(1, 2, 3)}};
  EXPECT_THROW(make_element_frame(coincident), DegenerateTriangle);
  // A sliver well below the 1e-12 relative area criterion.
  const SpatialTriangle sliver = {
      {Point<3>(0, 0, 0), Point<3>(1, 0, 0), Point<3>(0.5, 1e-14, 0)}};
  EXPECT_THROW(make_element_frame(sliver), DegenerateTriangle);

  const PlanarTriangle planar = {
      {Point<2>(0, 0), Point<2>(1, 2), Point<2>(2, 4)}};
  EXPECT_THROW(barycentric_gradients(planar), DegenerateTriangle);
}
