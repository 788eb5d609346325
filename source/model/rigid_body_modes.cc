#include <coshell/model/rigid_body_modes.h>

#include <deal.II/lac/lapack_full_matrix.h>

#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace coshell::model
{
  using namespace dealii;

  std::array<Vector<double>, 6> rigid_body_modes(const ShellModel &model)
  {
    const auto  &vertices = model.surface().get_vertices();
    Point<3>     centre;
    unsigned int n_used = 0;
    for (unsigned int v = 0; v < vertices.size(); ++v)
      if (model.vertex_is_used(v))
      {
        centre += vertices[v];
        ++n_used;
      }
    centre /= n_used;
    double size = 0;
    for (unsigned int v = 0; v < vertices.size(); ++v)
      if (model.vertex_is_used(v))
        size = std::max(size, vertices[v].distance(centre));

    std::array<Vector<double>, 6> modes;
    for (auto &mode : modes)
      mode.reinit(model.n_dofs());
    for (unsigned int v = 0; v < vertices.size(); ++v)
      if (model.vertex_is_used(v))
      {
        const VertexDofs  &dofs = model.vertex_dofs(v);
        const Tensor<1, 3> arm  = (vertices[v] - centre) / size;
        for (unsigned int axis = 0; axis < 3; ++axis)
        {
          Tensor<1, 3> omega;
          omega[axis]             = 1;
          const Tensor<1, 3> u    = cross_product_3d(omega, arm);
          modes[axis][dofs[axis]] = 1;
          for (unsigned int d = 0; d < 3; ++d)
            modes[3 + axis][dofs[d]] = u[d];
          modes[3 + axis][dofs[rx + axis]] = 1.0 / size;
        }
      }
    return modes;
  }

  namespace
  {
    /// The rigid-body motions the constraints leave free: the null space
    /// of G = A^T A, A having one row per constraint line, the amount by
    /// which each of the six rigid modes violates that line. Returns the
    /// free motions as columns of coefficients of the six modes.
    FullMatrix<double>
    free_motions(const ShellModel                &model,
                 const AffineConstraints<double> &constraints)
    {
      const auto               modes = rigid_body_modes(model);
      LAPACKFullMatrix<double> gram(6, 6);
      for (const auto &line : constraints.get_lines())
      {
        std::array<double, 6> violation;
        for (unsigned int k = 0; k < 6; ++k)
        {
          violation[k] = modes[k][line.index];
          for (const auto &[column, weight] : line.entries)
            violation[k] -= weight * modes[k][column];
        }
        for (unsigned int i = 0; i < 6; ++i)
          for (unsigned int j = 0; j < 6; ++j)
            gram(i, j) += violation[i] * violation[j];
      }
      const double       scale = std::max(1.0, gram.frobenius_norm());
      Vector<double>     free_amounts;
      FullMatrix<double> free_modes;
      gram.compute_eigenvalues_symmetric(-1.0, 1e-10 * scale, 1e-14 * scale,
                                         free_amounts, free_modes);
      if (free_amounts.size() == 0)
        return FullMatrix<double>();
      return free_modes;
    }
  } // namespace

  unsigned int
  n_free_rigid_motions(const ShellModel                &model,
                       const AffineConstraints<double> &constraints)
  {
    return free_motions(model, constraints).n();
  }

  void check_supports(const ShellModel                &model,
                      const AffineConstraints<double> &constraints)
  {
    const FullMatrix<double> free_modes = free_motions(model, constraints);
    if (free_modes.n() == 0)
      return;
    static const char *names[6] = {"translation x", "translation y",
                                   "translation z", "rotation x",
                                   "rotation y",    "rotation z"};
    std::ostringstream motion;
    motion << std::setprecision(2);
    const char *plus = "";
    for (unsigned int k = 0; k < 6; ++k)
      if (std::abs(free_modes(k, 0)) > 1e-3)
      {
        motion << plus << free_modes(k, 0) << " " << names[k];
        plus = " + ";
      }
    throw std::runtime_error(
        "the boundary conditions leave " + std::to_string(free_modes.n()) +
        " rigid-body motion(s) free, e.g. " + motion.str() +
        ": the stiffness would be singular. Add supports in 'Boundary "
        "conditions/Conditions'.");
  }
} // namespace coshell::model
