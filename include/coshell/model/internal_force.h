#pragma once

#include <coshell/element/corotational.h>
#include <coshell/model/contribution.h>
#include <coshell/model/element_parameters.h>
#include <coshell/model/shell_model.h>

#include <vector>

namespace coshell::model
{
  /// The elastic internal force of the shell and its tangent, with linear
  /// kinematics (f = K u on the initial geometry) or with the
  /// element-independent co-rotational frame (finite rotations).
  class InternalForce : public Contribution
  {
  public:
    InternalForce(const ShellModel            &model,
                  Formulation                  kinematics,
                  element::CorotationalTangent tangent);

    std::string name() const override;
    ForceKind   kind() const override;
    bool        has_cell_terms() const override;
    void        add_cell(const CellIterator    &cell,
                         const EvaluationPoint &point,
                         CellContribution      &contribution,
                         bool                   with_tangent) const override;
    bool        symmetric_tangent() const override;

    /// Elastic energy stored in the shell, J (force x length).
    double strain_energy(const ShellState &state) const;

    /// Membrane forces and bending moments of every active cell.
    std::vector<element::ShellResultants>
    resultants(const ShellState &state) const;

  private:
    const ShellModel                       &model_;
    Formulation                             kinematics_;
    element::CorotationalTangent            tangent_;
    std::vector<element::CorotationalShell> corotational_;

    element::NodalRotations nodal_rotations(const CellIterator &cell,
                                            const ShellState   &state) const;
    double cell_energy(const CellIterator &cell, const ShellState &state) const;
  };

  /// The largest principal membrane strain and bending surface strain
  /// (h/2 times the principal curvature) over the cells, in magnitude,
  /// recovered from the resultants through each cell's isotropic material.
  struct LargestStrains
  {
    double membrane = 0, bending = 0;
  };
  LargestStrains
  largest_strains(const ShellModel                            &model,
                  const std::vector<element::ShellResultants> &resultants);

  /// The triangle of a cell in the current configuration of 'state'.
  element::SpatialTriangle current_triangle(const ShellModel   &model,
                                            const CellIterator &cell,
                                            const ShellState   &state);
} // namespace coshell::model
