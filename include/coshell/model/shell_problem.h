#pragma once

#include <coshell/base/nonlinear_problem.h>
#include <coshell/model/contribution.h>
#include <coshell/model/direct_scatter.h>
#include <coshell/model/shell_model.h>
#include <coshell/model/shell_state.h>

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/thread_management.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>

#include <array>
#include <cstdint>
#include <exception>
#include <functional>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

namespace coshell::model
{
  /// (DoF, increment still needed to reach its prescribed value) pairs.
  using PrescribedIncrements =
      std::vector<std::pair<dealii::types::global_dof_index, double>>;
  /// Fills the increments that take the prescribed DoFs from 'state' to
  /// their values at 'time'.
  using PrescribedIncrementFunction = std::function<void(
      double time, const ShellState &state, PrescribedIncrements &increments)>;

  /// Bounds on one Newton correction of the shell (prm subsection
  /// "Nonlinear solver", declared here because only the shell knows which
  /// unknowns are rotations). A correction that would turn some vertex by
  /// more than the bound is scaled down, translations with it, as the
  /// contact filter scales it: a trust region on the rotations.
  struct CorrectionLimits
  {
    /// rad; 0: no bound.
    double largest_rotation = 0;

    static void declare_parameters(dealii::ParameterHandler &prm);
    void        parse_parameters(dealii::ParameterHandler &prm);
  };

  /// The shell as a nonlinear problem: the configuration, the constraints
  /// (supports and prescribed motions) and the sum of the active
  /// contributions. Prescribed motions enter as inhomogeneous constraints
  /// while the prescribed DoFs have not reached their values, that is on
  /// the first Newton iteration of a step (as in deal.II's step-44).
  class ShellProblem : public base::EvolutionProblem
  {
  public:
    /// 'constraints' must be closed and homogeneous, and contain a line for
    /// every DoF that 'prescribed' may name. 'state' must outlive this.
    ShellProblem(const ShellModel                          &model,
                 ShellState                                &state,
                 const dealii::AffineConstraints<double>   &constraints,
                 std::vector<std::unique_ptr<Contribution>> contributions,
                 PrescribedIncrementFunction                prescribed = {});

    /// How the path parameter s of a static stage maps to time and load
    /// factor: t = start + s * duration, lambda = load_factor(t, s).
    struct Schedule
    {
      double                                start_time = 0, duration = 1;
      std::function<double(double, double)> load_factor = [](double, double s)
      { return s; };
    };
    void set_schedule(const Schedule &schedule);
    void set_correction_limits(const CorrectionLimits &limits);
    /// Dynamics: the load factor at time t (defaults to the schedule's).
    double time() const;
    double load_factor() const;

    // base::NonlinearProblem
    const dealii::SparsityPattern &sparsity() const override;
    /// Under mpirun each rank holds its rows of the tangent and assembles
    /// its cells into it (a distributed Trilinos matrix).
    void reinit_tangent(base::TangentMatrix &tangent) const override;
    /// Grows the pattern by the vertex couplings the contributions ask
    /// for (self contact); rebuilt only when they change.
    void begin_solve() override;
    void evaluate(dealii::Vector<double> &residual,
                  base::TangentMatrix    *tangent) override;
    /// The sum of the contributions' energies (cells over the ranks);
    /// NaN unless every contribution has a potential.
    double energy() override;
    double force_scale() const override;
    bool   prescribed_increment_pending() const override;
    bool   prescribed_move_blocked() const override;
    void   distribute(dealii::Vector<double> &correction) const override;
    void   apply_increment(const dealii::Vector<double> &correction) override;
    double admissible_fraction(
        const dealii::Vector<double> &correction) const override;
    void extrapolate_reports(const dealii::Vector<double> &correction) override;
    void save() override;
    void restore() override;
    void begin_trial() override;
    void end_trial() override;
    void keep_trial() override;
    bool symmetric_tangent() const override;
    bool use_convex_tangent() override;
    std::string failure_context() const override;

    // base::EvolutionProblem
    void set_path_parameter(double s) override;
    void path_direction(dealii::Vector<double> &direction) override;
    void set_time(double time) override;
    void step_increment(dealii::Vector<double> &increment) const override;
    void set_step_increment(const dealii::Vector<double> &increment) override;
    void step_displacement(const dealii::Vector<double> &increment,
                           dealii::Vector<double> &displacement) const override;
    void
    set_step_displacement(const dealii::Vector<double> &displacement) override;
    dealii::Vector<double> &velocity() override;
    dealii::Vector<double> &acceleration() override;
    void set_rate_coefficients(double acceleration_coefficient,
                               double velocity_coefficient) override;
    void mass_matrix(base::TangentMatrix &mass) override;

    /// Wall-clock seconds spent in evaluate() so far (assembly).
    double assembly_seconds() const;

    const ShellState &state() const;
    /// The largest force scale of the stage's converged states, which
    /// Newton's convergence test never goes below, counting the current
    /// state as save() would; a restart sets it back.
    double            converged_force_scale() const;
    void              set_converged_force_scale(double scale);
    const ShellModel &model() const;
    const dealii::AffineConstraints<double> &constraints() const;

    /// The active contribution of type T, or nullptr.
    template<typename T>
    const T *find() const
    {
      for (const auto &contribution : contributions_)
        if (const auto *found = dynamic_cast<const T *>(contribution.get()))
          return found;
      return nullptr;
    }

    /// Unconstrained force of the contributions of one kind at the last
    /// evaluate() (e.g. the external loads, for the work they do; the
    /// internal force, whose constrained entries are the reactions).
    const dealii::Vector<double> &force(ForceKind kind) const;

  private:
    const ShellModel &model_;
    ShellState       &state_;
    /// The iterate at begin_trial(), put back exactly by end_trial() (an
    /// opposite increment leaves round-off, which would keep contact from
    /// recognising the trial's shape when Newton moves there).
    std::optional<ShellState>                  trial_start_;
    dealii::AffineConstraints<double>          constraints_, homogeneous_;
    std::vector<std::unique_ptr<Contribution>> contributions_;
    PrescribedIncrementFunction                prescribed_;
    dealii::SparsityPattern                    sparsity_;
    /// Names sparsity_'s present contents for the tangents kept across
    /// solves (base::TangentMatrix::reinit): new, unique in the
    /// process, each time it is made.
    std::uint64_t sparsity_version_ = 0;
    /// Under mpirun: this rank's rows of the same pattern.
    std::unique_ptr<dealii::TrilinosWrappers::SparsityPattern>
         distributed_sparsity_;
    void make_sparsities();
    /// The extra vertex couplings sparsity_ was built with, sorted, and
    /// the generations of the contributions' lists they came from.
    std::vector<std::array<unsigned int, 2>> coupled_vertices_;
    std::vector<std::uint64_t>               coupling_generations_;
    mutable dealii::FullMatrix<double>       trimmed_;
    /// Adds contact blocks where no DoF is constrained (free-flying
    /// scenes).
    DirectScatter scatter_;
    /// Adds the cells' matrices where no DoF is constrained; its map
    /// follows sparsity_.
    CellScatter cell_scatter_;
    /// The evaluation's tangent takes only the entries with column <= row
    /// (base::TangentMatrix::set_lower_only()); set while evaluate()
    /// assembles.
    bool lower_only_ = false;
    /// Adds a cell's matrix (and vector, if given) into 'tangent'.
    template<typename Matrix>
    void add_cell_terms(const CellContribution &copy,
                        Matrix                 &tangent,
                        dealii::Vector<double> *residual);
    /// Adds a contact block through scatter_ if the tangent is a deal.II matrix
    /// (or none) and no DoF is constrained; returns whether it did.
    template<typename Matrix>
    bool
         scatter_directly(const dealii::FullMatrix<double>                   &matrix,
                          const dealii::Vector<double>                       &vector,
                          const std::vector<dealii::types::global_dof_index> &dofs,
                          Matrix                 *tangent,
                          dealii::Vector<double> *residual);
    bool couples_beyond_cells_ = false;
    const dealii::FullMatrix<double>                  &
    within_pattern(const DofBlock &block) const;
    Schedule         schedule_;
    CorrectionLimits correction_limits_;
    double           time_ = 0, load_factor_ = 0;
    double           acceleration_coefficient_ = 0, velocity_coefficient_ = 0;
    std::array<dealii::Vector<double>, n_force_kinds> forces_;
    /// On several ranks: this rank's share of the cell forces by kind.
    std::array<dealii::Vector<double>, n_force_kinds> rank_forces_;
    bool                                              pending_ = false;
    bool                                              blocked_ = false;
    double                 converged_force_scale_              = 0;
    double                 force_floor_                        = 0;
    double                 assembly_seconds_                   = 0;
    PrescribedIncrements   increments_;
    dealii::Vector<double> global_force_, one_global_force_;

    EvaluationPoint point() const;
    /// The largest fraction of 'correction' within correction_limits_.
    double
    rotation_limit_fraction(const dealii::Vector<double> &correction) const;
    double current_force_scale() const;
    void   update_inhomogeneities();
    /// Calls every contribution's prepare(). Those with cell terms do so
    /// now; the others (contact's pair search) on the returned task, which
    /// with several threads runs beside the cells' assembly and then
    /// makes their blocks too, into made_blocks_. It reads the state and
    /// writes only those contributions' own records, which the cells do
    /// not touch. Join it before their blocks are added.
    dealii::Threads::Task<std::exception_ptr>
    prepare_contributions(const EvaluationPoint &at, bool with_tangent);
    /// The blocks one contribution made on the preparation task, in the
    /// order it made them; the storage is kept between evaluations.
    struct MadeBlocks
    {
      std::vector<DofBlock> blocks;
      unsigned int          count = 0;
      void                  keep(const DofBlock &block);
    };
    /// Per contribution. Used with several threads only: on one, the task
    /// runs at once and the blocks go straight into the matrix.
    std::vector<MadeBlocks> made_blocks_;
    bool                    blocks_made_on_task_ = false;
    /// Joins 'preparation' (rethrowing what it threw) and notes whether a
    /// contribution holds a prescribed move back.
    void
    finish_preparation(dealii::Threads::Task<std::exception_ptr> &preparation);
    /// Adds the blocks of the contributions (contact pairs): those the
    /// preparation task of this evaluation made, else made now. Every rank
    /// finds the same blocks; a distributed tangent takes each row from the
    /// rank that owns it (base::RowsOf).
    template<typename Matrix>
    void assemble_blocks(const EvaluationPoint  &at,
                         dealii::Vector<double> &residual,
                         Matrix                 *tangent);
    /// Runs the cell terms of the contributions 'use' selects. On several
    /// ranks each assembles the cells it owns; the residual and a complete
    /// (deal.II) tangent are then added up over the ranks, so they must be
    /// zero on entry. A distributed tangent needs compress() afterwards.
    template<typename Matrix>
    void assemble(const std::function<bool(const Contribution &)> &use,
                  const EvaluationPoint                           &at,
                  dealii::Vector<double>                          *residual,
                  Matrix                                          *tangent);
    void add_up_over_ranks(dealii::Vector<double>       *residual,
                           dealii::SparseMatrix<double> *tangent);
    void add_up_over_ranks(dealii::Vector<double>                 *residual,
                           dealii::TrilinosWrappers::SparseMatrix *tangent);
  };
} // namespace coshell::model
