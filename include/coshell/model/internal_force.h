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
    /// With 'extrapolated_forces' (co-rotational only), the geometric
    /// terms of a cell's tangent use its local forces extrapolated from its
    /// previous tangent evaluation: K_l (d + J dp), where d and J = dd/dp
    /// were that evaluation's and dp leads from its configuration to the
    /// current one (Magisano, Leonetti & Garcea 2017). The force is exact
    /// either way. begin_solve() and restore() forget the previous
    /// evaluations: a step starts from the exact forces, so that a run
    /// restarted from a checkpoint takes the uninterrupted run's iterates.
    /// With 'exact_after_failure' (Geometric stiffness = auto), once
    /// restore() has been called (a step failed) the rest of the stage
    /// uses the current forces, the exact tangent.
    InternalForce(const ShellModel            &model,
                  Formulation                  kinematics,
                  element::CorotationalTangent tangent,
                  bool                         extrapolated_forces = false,
                  bool                         exact_after_failure = false);

    std::string name() const override;
    ForceKind   kind() const override;
    bool        has_cell_terms() const override;
    void        add_cell(const CellIterator    &cell,
                         const EvaluationPoint &point,
                         CellContribution      &contribution,
                         bool                   with_tangent) const override;
    bool        symmetric_tangent() const override;
    /// The strain energy: the force is its gradient (the tangent its
    /// Hessian with the consistent tangent, the Hessian's symmetric part
    /// with the symmetric one).
    bool   has_potential() const override;
    double cell_energy(const CellIterator    &cell,
                       const EvaluationPoint &point) const override;
    void   begin_solve() override;
    void   restore() override;

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

    /// A cell's configuration at its last tangent evaluation, with the
    /// linearization there and the deformational DOFs its geometric
    /// terms used (see add_corotational_cell()).
    struct TangentHistory
    {
      bool                               valid = false;
      element::SpatialTriangle           triangle;
      element::NodalRotations            rotations;
      element::CorotationalLinearization linearization;
      element::ShellDisplacements        geometric_dofs{};
    };
    bool extrapolate_ = false;
    /// The extrapolation is a first-order model; where a step of the
    /// stage has failed, Newton is in a regime it can mislead (the whole
    /// roll-up in one step: 90 corrections with it, 71 without), so the
    /// rest of the stage takes the exact tangent.
    bool                                exact_after_failure_ = false;
    bool                                a_step_failed_       = false;
    mutable std::vector<TangentHistory> history_;

    void forget_history();
    void add_corotational_cell(const CellIterator    &cell,
                               const EvaluationPoint &point,
                               CellContribution      &contribution,
                               bool                   with_tangent) const;

    double strain_energy(const CellIterator &cell,
                         const ShellState   &state) const;
  };

  /// The strains of one cell, recovered from its resultants through its
  /// isotropic material, each the largest principal value in magnitude:
  /// the mid-surface (membrane) strain, the bending strain at the surfaces
  /// (h/2 times the curvature), and the strain at the upper or lower
  /// surface, the tensor sum of the two, which is what the material there
  /// undergoes (less than membrane + bending when their principal axes
  /// differ).
  struct CellStrains
  {
    double membrane = 0, bending = 0, surface = 0;
  };
  CellStrains cell_strains(const element::ShellMaterial   &material,
                           const element::ShellResultants &resultants);

  /// The largest of each of a cell's strains (cell_strains) over the
  /// cells.
  struct LargestStrains
  {
    double membrane = 0, bending = 0, surface = 0;
  };
  LargestStrains
  largest_strains(const ShellModel                            &model,
                  const std::vector<element::ShellResultants> &resultants);

  /// The rotation matrices of a cell's vertices in 'state'.
  element::NodalRotations nodal_rotations(const CellIterator &cell,
                                          const ShellState   &state);

  /// The triangle of a cell in the current configuration of 'state'.
  element::SpatialTriangle current_triangle(const ShellModel   &model,
                                            const CellIterator &cell,
                                            const ShellState   &state);
} // namespace coshell::model
