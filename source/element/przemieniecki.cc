// The paper's plate element (Comas et al. 2010, section 2.2): Przemieniecki's
// incomplete cubic with the x^2 y term removed,
//   w = c1 + c2 x + c3 y + c4 x^2 + c5 xy + c6 y^2 + c7 x^3 + c8 xy^2 + c9 y^3,
// in the coordinates the caller passes. The coefficients follow from the
// nodal DOFs (w, dw/dy, -dw/dx) through u = C c, eq. (4).

#include <coshell/element/bending.h>

#include <deal.II/lac/lapack_full_matrix.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace coshell::element
{
  namespace
  {
    constexpr unsigned int n_terms = 9;

    // Below this reciprocal condition number (of C in coordinates scaled by
    // the longest edge) C^-1 has lost most of its digits.
    constexpr double singular_tolerance = 1e-12;

    // The three rows of C for a vertex at p: (w, dw/dy, -dw/dx) of each
    // monomial 1, x, y, x^2, xy, y^2, x^3, xy^2, y^3.
    void add_vertex_rows(const Point<2>     &p,
                         unsigned int        vertex,
                         FullMatrix<double> &interpolation)
    {
      const double x = p[0], y = p[1];
      const double rows[3][n_terms] = {
          {1, x, y, x * x, x * y, y * y, x * x * x, x * y * y, y * y * y},
          {0, 0, 1, 0, x, 2 * y, 0, 2 * x * y, 3 * y * y},
          {0, -1, 0, -2 * x, -y, 0, -3 * x * x, -y * y, 0}};
      for (unsigned int r = 0; r < 3; ++r)
        for (unsigned int k = 0; k < n_terms; ++k)
          interpolation(3 * vertex + r, k) = rows[r][k];
    }

    // (w_xx, w_yy, 2 w_xy) of each monomial at p, eq. (10).
    FullMatrix<double> monomial_curvatures(const Point<2> &p)
    {
      FullMatrix<double> curvatures(3, n_terms);
      curvatures(0, 3) = 2.0;
      curvatures(0, 6) = 6.0 * p[0];
      curvatures(1, 5) = 2.0;
      curvatures(1, 7) = 2.0 * p[0];
      curvatures(1, 8) = 6.0 * p[1];
      curvatures(2, 4) = 2.0;
      curvatures(2, 7) = 4.0 * p[1];
      return curvatures;
    }

    double reciprocal_condition(const FullMatrix<double> &matrix)
    {
      dealii::LAPACKFullMatrix<double> svd(matrix.m(), matrix.n());
      svd = matrix;
      svd.compute_svd();
      return svd.singular_value(matrix.n() - 1) / svd.singular_value(0);
    }

    [[noreturn]] void report_singular(const PlanarTriangle &triangle,
                                      double                condition)
    {
      std::ostringstream message;
      message << "Przemieniecki element: interpolation matrix C is singular "
                 "for the triangle ("
              << triangle[0] << "; " << triangle[1] << "; " << triangle[2]
              << ") in the coordinates given (reciprocal condition number "
              << condition << ")";
      throw DegenerateTriangle(message.str());
    }
  } // namespace

  std::vector<FullMatrix<double>>
  przemieniecki_curvature_matrices(const PlanarTriangle        &triangle,
                                   const std::vector<Point<2>> &points)
  {
    // Work in x / L so that the entries of C (1 ... L^3) are all O(1): the
    // condition number then measures the geometry, not the length unit.
    // In scaled coordinates the slope DOFs are L theta and the
    // curvatures are L^2 times the physical ones.
    const double length =
        std::sqrt(std::max({triangle[0].distance_square(triangle[1]),
                            triangle[1].distance_square(triangle[2]),
                            triangle[2].distance_square(triangle[0])}));

    FullMatrix<double> interpolation(n_terms, n_terms);
    for (unsigned int i = 0; i < 3; ++i)
      add_vertex_rows(triangle[i] / length, i, interpolation);
    const double condition = reciprocal_condition(interpolation);
    if (!(condition > singular_tolerance))
      report_singular(triangle, condition);

    // c' = C'^-1 S u with S = diag(1, L, L) per vertex.
    FullMatrix<double> coefficients(n_terms, n_terms);
    coefficients.invert(interpolation);
    for (unsigned int k = 0; k < n_terms; ++k)
      for (unsigned int d = 0; d < n_terms; ++d)
        coefficients(k, d) *= (d % 3 == 0) ? 1.0 : length;

    // kappa = -(w_xx, w_yy, 2 w_xy), the sign convention of BendingMoments.
    std::vector<FullMatrix<double>> result;
    result.reserve(points.size());
    for (const Point<2> &p : points)
    {
      FullMatrix<double> kappa(3, n_terms);
      monomial_curvatures(p / length).mmult(kappa, coefficients);
      kappa *= -1.0 / (length * length);
      result.push_back(kappa);
    }
    return result;
  }

  FullMatrix<double> przemieniecki_stiffness(const PlanarTriangle &triangle,
                                             const ShellMaterial  &material)
  {
    return bending_stiffness(BendingElement::przemieniecki, triangle, material);
  }
} // namespace coshell::element
