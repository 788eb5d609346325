#pragma once

#include <coshell/element/corotational.h>
#include <coshell/model/cell_loop.h>
#include <coshell/model/shell_model.h>
#include <coshell/model/shell_state.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>

#include <vector>

namespace coshell::model
{
  /// Co-rotational (EICR) shell: the linear element kernels carried by a
  /// frame that follows each triangle. Evaluates the residual and tangent
  /// of a configuration; knows nothing of load stepping.
  class CorotationalModel
  {
  public:
    explicit CorotationalModel(const ShellModel &model);

    /// residual = load_factor * (dead_load + follower pressure at the
    /// current configuration) - internal force, condensed with the
    /// (homogeneous) constraints; when 'tangent' is given, also
    /// d(internal - follower)/d(increment). 'dead_load' must be unscaled.
    void assemble(const ShellState                        &state,
                  double                                   load_factor,
                  const dealii::Vector<double>            &dead_load,
                  double                                   follower_pressure,
                  element::CorotationalTangent             tangent_type,
                  const dealii::AffineConstraints<double> &constraints,
                  dealii::Vector<double>                  &residual,
                  dealii::SparseMatrix<double>            *tangent) const;

    /// External load vector at the current configuration (dead + follower),
    /// for the arc-length method's load direction.
    void load_vector(const ShellState             &state,
                     const dealii::Vector<double> &dead_load,
                     double                        follower_pressure,
                     dealii::Vector<double>       &load) const;

    std::vector<element::ShellResultants>
    resultants(const ShellState &state) const;

  private:
    const ShellModel                       &model_;
    std::vector<element::CorotationalShell> elements_;

    element::SpatialTriangle current_triangle(const CellIterator &cell,
                                              const ShellState   &state) const;
    element::NodalRotations  nodal_rotations(const CellIterator &cell,
                                             const ShellState   &state) const;
    void                     add_follower_pressure(const CellIterator &cell,
                                                   const ShellState   &state,
                                                   double              pressure,
                                                   CellContribution   &contribution,
                                                   bool                with_stiffness) const;
  };
} // namespace coshell::model
