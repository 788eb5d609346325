#include <coshell/contact/barrier.h>

#include <cmath>
#include <stdexcept>

namespace coshell::contact
{
  ScalarDerivatives log_barrier(double g, double g_hat)
  {
    if (g >= g_hat)
      return {};
    if (!(g > 0))
      return {std::numeric_limits<double>::infinity(),
              -std::numeric_limits<double>::infinity(),
              std::numeric_limits<double>::infinity()};
    const double x = g - g_hat, log_ratio = std::log(g / g_hat);
    return {-x * x * log_ratio, -2 * x * log_ratio - x * x / g,
            -2 * log_ratio - 4 * x / g + x * x / (g * g)};
  }

  ScalarDerivatives smoothed_penalty(double g, double eps)
  {
    const double x = -g; // penetration
    if (x <= 0)
      return {};
    if (x <= eps)
      return {x * x * x / (6 * eps), -x * x / (2 * eps), x / eps};
    return {x * x / 2 - eps * x / 2 + eps * eps / 6, -(x - eps / 2), 1};
  }

  namespace
  {
    /// Eigenvalues (diagonal of a) and eigenvectors (columns of v) of the
    /// symmetric matrix a by cyclic Jacobi sweeps.
    void
    jacobi_eigen(std::vector<double> &a, std::vector<double> &v, unsigned int n)
    {
      v.assign(n * n, 0);
      for (unsigned int i = 0; i < n; ++i)
        v[i * n + i] = 1;
      for (unsigned int sweep = 0; sweep < 50; ++sweep)
      {
        double off = 0, diagonal = 0;
        for (unsigned int i = 0; i < n; ++i)
        {
          diagonal += a[i * n + i] * a[i * n + i];
          for (unsigned int j = i + 1; j < n; ++j)
            off += a[i * n + j] * a[i * n + j];
        }
        if (off <= 1e-30 * diagonal || off == 0)
          return;
        for (unsigned int p = 0; p < n; ++p)
          for (unsigned int q = p + 1; q < n; ++q)
          {
            const double apq = a[p * n + q];
            if (apq == 0)
              continue;
            const double theta = (a[q * n + q] - a[p * n + p]) / (2 * apq);
            const double t     = (theta >= 0 ? 1 : -1) /
                             (std::abs(theta) + std::sqrt(theta * theta + 1));
            const double c = 1 / std::sqrt(t * t + 1), s = t * c;
            for (unsigned int k = 0; k < n; ++k) // a <- a J
            {
              const double akp = a[k * n + p], akq = a[k * n + q];
              a[k * n + p] = c * akp - s * akq;
              a[k * n + q] = s * akp + c * akq;
            }
            for (unsigned int k = 0; k < n; ++k) // a <- J^T a
            {
              const double apk = a[p * n + k], aqk = a[q * n + k];
              a[p * n + k] = c * apk - s * aqk;
              a[q * n + k] = s * apk + c * aqk;
            }
            for (unsigned int k = 0; k < n; ++k)
            {
              const double vkp = v[k * n + p], vkq = v[k * n + q];
              v[k * n + p] = c * vkp - s * vkq;
              v[k * n + q] = s * vkp + c * vkq;
            }
          }
      }
    }
  } // namespace

  void project_to_positive_semidefinite(std::vector<double> &matrix,
                                        unsigned int         n)
  {
    if (matrix.size() != n * n)
      throw std::logic_error("project_to_positive_semidefinite: size");
    std::vector<double> a = matrix, v;
    jacobi_eigen(a, v, n);
    bool definite = true;
    for (unsigned int i = 0; i < n; ++i)
      definite = definite && a[i * n + i] >= 0;
    if (definite)
      return;
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = 0; j < n; ++j)
      {
        double sum = 0;
        for (unsigned int k = 0; k < n; ++k)
          sum += v[i * n + k] * std::max(a[k * n + k], 0.0) * v[j * n + k];
        matrix[i * n + j] = sum;
      }
  }
} // namespace coshell::contact
