#pragma once

#include <coshell/element/corotational.h>
#include <coshell/element/thick_membrane.h>
#include <coshell/model/contribution.h>
#include <coshell/model/shell_model.h>
#include <coshell/model/shell_problem.h>

#include <vector>

namespace coshell::model
{
  /// Element/Thickness stretch: every cell's thick membrane
  /// (element::ThickMembrane) on its vertices' translations and thickness
  /// stretches, and its bending at the current thickness, as one block per
  /// cell on its 18 shell DoFs and 3 stretches. The internal force keeps
  /// the CST's drilling penalty and bending at h0; this adds
  /// (s - 1) E_b with s = (lambda_0^3 + lambda_1^3 + lambda_2^3) / 3, the
  /// vertex rule for D(h) / D(h0), and E_b the co-rotational bending
  /// energy at h0. Its tangent is the symmetric co-rotational one.
  class ThickMembraneForce : public Contribution
  {
  public:
    explicit ThickMembraneForce(const ShellModel &model);

    std::string name() const override;
    ForceKind   kind() const override;
    bool        has_cell_terms() const override;
    void        add_blocks(const EvaluationPoint &point,
                           const BlockSink       &sink,
                           bool                   with_tangent) override;
    bool        symmetric_tangent() const override;
    bool        has_potential() const override;
    double      global_energy(const EvaluationPoint &point) const override;
    /// The thick membranes' energy and the bending change, N mm.
    double energy(const ShellState &state) const;
    /// The largest fraction of 'correction' that leaves every stretch at
    /// least a fifth of what it is: the law's energy is infinite at
    /// lambda = 0, where a barrier's push on a vertex of small area would
    /// otherwise send a full Newton step.
    double admissible_fraction(
        const ShellState             &state,
        const dealii::Vector<double> &correction) const override;

  private:
    const ShellModel                   &model_;
    std::vector<element::ThickMembrane> membranes_;
    /// Bending only, at h0 (empty with Bending element = off).
    std::vector<element::CorotationalShell> bending_;

    std::array<double, 3> stretches(const CellIterator &cell,
                                    const ShellState   &state) const;
    /// The cell's 18 shell DoFs and then its 3 stretch DoFs.
    void cell_dofs(const CellIterator                           &cell,
                   std::vector<dealii::types::global_dof_index> &dofs) const;
    /// A cell's current vertex positions and stretches, read once per
    /// evaluation for both of its terms.
    struct CellConfiguration
    {
      element::SpatialTriangle positions;
      std::array<double, 3>    stretches;
    };
    CellConfiguration configuration(const CellIterator &cell,
                                    const ShellState   &state) const;
    void              add_membrane(const CellIterator      &cell,
                                   const CellConfiguration &at,
                                   DofBlock                &block,
                                   bool                     with_tangent) const;
    void              add_bending_change(const CellIterator      &cell,
                                         const ShellState        &state,
                                         const CellConfiguration &at,
                                         DofBlock                &block,
                                         bool                     with_tangent) const;
  };

  /// Element/Face pressure: a nominal pressure P on both faces, force per
  /// reference area, times the load factor. It is dead in the thickness
  /// stretch: its potential is P A0 h0 (lambda - 1) summed by the vertex
  /// rule (the plates' work is P A0 (h0 - h)), so their force on a cell
  /// is P A0.
  class FacePressure : public Contribution
  {
  public:
    FacePressure(const ShellModel &model, double pressure);

    std::string name() const override;
    ForceKind   kind() const override;
    bool        has_cell_terms() const override;
    void        add_global(const EvaluationPoint  &point,
                           dealii::Vector<double> &residual) const override;
    bool        symmetric_tangent() const override;
    bool        has_potential() const override;
    double      global_energy(const EvaluationPoint &point) const override;

  private:
    const ShellModel &model_;
    /// P A0 h0 / 3 summed over the cells around each vertex, in the
    /// thickness DoFs (N mm per unit stretch at P).
    dealii::Vector<double> load_;
  };
  /// The energy stored in the shell at 'state', N mm: the internal force's
  /// strain energy and, with the thickness stretch, the thick membrane's.
  double stored_energy(const ShellProblem &problem, const ShellState &state);
} // namespace coshell::model
