#pragma once

#include <coshell/element/mass.h>
#include <coshell/model/contribution.h>
#include <coshell/model/element_parameters.h>
#include <coshell/model/shell_model.h>

#include <deal.II/base/parameter_handler.h>

#include <string>
#include <vector>

namespace coshell::model
{
  /// prm subsection "Mass and damping".
  struct InertiaParameters
  {
    element::MassMatrix mass_matrix           = element::MassMatrix::consistent;
    double              rotary_inertia_factor = 1;
    double              rayleigh_alpha = 0, rayleigh_beta = 0;
    double              normal_drag = 0, tangential_drag = 0;
    /// Muparser expressions of x, y, z (three each, ';'-separated).
    std::string initial_velocity         = "0; 0; 0";
    std::string initial_angular_velocity = "0; 0; 0";

    static void declare_parameters(dealii::ParameterHandler &prm);
    /// Throws std::invalid_argument naming the parameter.
    void parse_parameters(dealii::ParameterHandler &prm);

    bool damped() const;
  };

  /// Kinetic quantities of a configuration with its rates.
  struct KineticMeasures
  {
    double               kinetic_energy = 0;
    dealii::Tensor<1, 3> linear_momentum, angular_momentum; ///< about 0
  };

  /// Inertia forces -M a (consistent or lumped translational mass, lumped
  /// isotropic rotary inertia, so no gyroscopic term), Rayleigh damping
  /// -(alpha M + beta K) v with K the linear stiffness of the current flat
  /// triangle (zero on rigid motions), and the viscous drag of the medium.
  /// Rotational rates are material (Omega); their spatial forms R Omega
  /// enter the forces. With body-frame translations (SE(3) integration) the
  /// translational rates are v = R^T dx/dt and dx/dt = R v,
  /// d2x/dt2 = R (dv/dt + Omega x v); the tangent then is not symmetric.
  class Inertia : public Contribution
  {
  public:
    Inertia(const ShellModel        &model,
            const InertiaParameters &parameters,
            bool                     body_frame_translations = false);

    std::string name() const override;
    ForceKind   kind() const override;
    bool        has_cell_terms() const override;
    void        add_cell(const CellIterator    &cell,
                         const EvaluationPoint &point,
                         CellContribution      &contribution,
                         bool                   with_tangent) const override;
    bool        symmetric_tangent() const override;
    /// The incremental potential of the time integrator, whose rates are
    /// affine in the step increment (acceleration c_a q + a_0, velocity
    /// c_v q + v_0): a.M a / (2 c_a) + v.C v / (2 c_v), with C taken at
    /// the current shape (its change is not differentiated, as in the
    /// tangent). Exact on translations. On rotations its gradient is the
    /// inertia force to first order in the step rotation
    /// (doc/theory/dynamics.md, "The incremental potential"). None with
    /// body-frame translations (SE3), whose force has no potential in
    /// these unknowns.
    bool   has_potential() const override;
    double cell_energy(const CellIterator    &cell,
                       const EvaluationPoint &point) const override;

    /// Kinetic energy and momenta.
    KineticMeasures measures(const ShellState &state) const;
    /// The force C v of the damping and drag (sized n_dofs), unconstrained,
    /// global axes; zero without them. Apart from measures(): a dynamic
    /// stage needs this force every step for the dissipated energy, the
    /// kinetic measures only on the rows of its time history.
    void damping_force(const ShellState       &state,
                       dealii::Vector<double> &force) const;

    /// Sets the velocities of 'state' from the initial-velocity expressions.
    void set_initial_velocity(ShellState &state) const;

  private:
    const ShellModel &model_;
    InertiaParameters parameters_;

    element::MassProperties mass_properties(const CellIterator &cell) const;
    /// Each active cell's mass entries (by active cell index), made by the
    /// constructor.
    std::vector<element::MassEntries> mass_entries_;
    const element::MassEntries &mass_entries(const CellIterator &cell) const;

    bool body_frame_translations_;

    enum class Rate
    {
      velocity,
      acceleration
    };
    using CellRates = std::array<double, element::shell_dofs>;
    /// The cell's mass and damping matrices times 'rates' (the layout of
    /// spatial_rates()), with only their nonzero entries where
    /// sparse_cell_matrices() holds.
    CellRates mass_times(const CellIterator &cell,
                         const ShellState   &state,
                         const CellRates    &rates) const;
    CellRates damping_times(const CellIterator &cell,
                            const ShellState   &state,
                            const CellRates    &rates) const;
    /// The cell's velocities or accelerations in global axes (rotations
    /// spatial).
    std::array<double, element::shell_dofs> spatial_rates(
        const CellIterator &cell, const ShellState &state, Rate rate) const;
    /// 'matrix' times d(spatial rate)/d(increment), block diagonal per
    /// vertex: 'coefficient' on every DoF (d rate / d q), and with
    /// body-frame translations the derivative of R w (w = v, or dv/dt +
    /// Omega x v with 'gyroscopic' = d v / d q) through the SE(3) step
    /// increment, translations and rotations.
    /// Into 'product'.
    void times_rate_jacobian(const dealii::FullMatrix<double> &matrix,
                             const CellIterator               &cell,
                             const ShellState                 &state,
                             Rate                              rate,
                             double                            coefficient,
                             double                            gyroscopic,
                             dealii::FullMatrix<double>       &product) const;
    /// The inertia's tangent (or, with point.rate_mass, the mass matrix in
    /// the rates' layout) added to 'matrix'.
    void add_inertia_tangent(const CellIterator               &cell,
                             const EvaluationPoint            &point,
                             const dealii::FullMatrix<double> &mass,
                             dealii::FullMatrix<double>       &matrix) const;
    /// Whether the cell matrices have the mass's structure at 'state' (no
    /// body-frame translations, no stiffness-proportional damping): then
    /// add_cell() and measures() take only their nonzero entries.
    bool sparse_cell_matrices(const ShellState &state) const;
    /// add_cell() where sparse_cell_matrices() holds.
    void add_sparse_cell(const CellIterator    &cell,
                         const EvaluationPoint &point,
                         CellContribution      &contribution,
                         bool                   with_tangent) const;
    /// The damping and drag matrix C of the cell into 'c' ('drag': room
    /// for the drag's 9x9 block).
    void damping(const CellIterator               &cell,
                 const element::SpatialTriangle   &current,
                 const dealii::FullMatrix<double> &mass,
                 dealii::FullMatrix<double>       &c,
                 dealii::FullMatrix<double>       &drag) const;
  };
} // namespace coshell::model
