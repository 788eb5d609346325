#pragma once

#include <coshell/model/contribution.h>
#include <coshell/model/loads.h>
#include <coshell/model/shell_model.h>

#include <ostream>

namespace coshell::model
{
  /// The loads of prm subsection "Loads", scaled by the load factor of the
  /// evaluation point: dead loads (a fixed vector) and, with finite
  /// rotations, a pressure that follows the deformed normals (with its
  /// load stiffness).
  class ExternalLoads : public Contribution
  {
  public:
    /// 'log' is told which vertex each point load snapped to.
    ExternalLoads(const ShellModel &model,
                  const Loads      &loads,
                  bool              finite_rotations,
                  std::ostream     &log);

    std::string name() const override;
    ForceKind   kind() const override;
    bool        has_cell_terms() const override;
    void        add_cell(const CellIterator    &cell,
                         const EvaluationPoint &point,
                         CellContribution      &contribution,
                         bool                   with_tangent) const override;
    void        add_global(const EvaluationPoint  &point,
                           dealii::Vector<double> &residual) const override;
    bool        symmetric_tangent() const override;
    /// The dead loads' potential -lambda f.u, unless a pressure follows
    /// the normals or a point moment acts on finite rotations: neither has
    /// a potential in these unknowns.
    bool   has_potential() const override;
    double global_energy(const EvaluationPoint &point) const override;

  private:
    const ShellModel      &model_;
    dealii::Vector<double> dead_load_;
    double                 follower_pressure_ = 0;
    /// Whether the dead loads include moments on finite rotations.
    bool moments_on_finite_rotations_ = false;
  };
} // namespace coshell::model
