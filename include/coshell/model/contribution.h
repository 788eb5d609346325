#pragma once

#include <coshell/model/cell_loop.h>
#include <coshell/model/shell_state.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include <string>

namespace coshell::model
{
  /// Where the residual is evaluated: the configuration (with its rates in
  /// dynamics), the time and the load factor, and how the rates depend on
  /// the increment.
  struct EvaluationPoint
  {
    const ShellState &state;
    /// Time, s (pseudo-time in statics).
    double time = 0;
    /// Dimensionless factor on the external loads.
    double load_factor = 1;
    /// d(acceleration)/d(increment), 1/s^2, and d(velocity)/d(increment),
    /// 1/s, of the time integrator; 0 in statics.
    double acceleration_coefficient = 0, velocity_coefficient = 0;
    /// Asks the inertia for d(force)/d(acceleration in the rates' layout),
    /// the mass matrix, instead of its tangent (they differ with
    /// body-frame translations).
    bool rate_mass = false;
  };

  /// What a force is, for the force scale of Newton's convergence test and
  /// the energy bookkeeping.
  enum class ForceKind : unsigned int
  {
    internal = 0,
    external = 1,
    inertia  = 2,
    contact  = 3
  };
  constexpr unsigned int n_force_kinds = 4;

  /// A force and stiffness block on DoFs that do not share a cell (a
  /// contact pair): 'vector' adds to r, 'matrix' to -dr/d(increment).
  struct DofBlock
  {
    std::vector<dealii::types::global_dof_index> dofs;
    dealii::Vector<double>                       vector;
    dealii::FullMatrix<double>                   matrix;
  };
  using BlockSink = std::function<void(const DofBlock &)>;

  /// One physical ingredient of the residual r = f_ext - f_int - f_inertia
  /// and of its tangent K = -dr/d(increment). An ingredient the scene does
  /// not switch on is never constructed, so it costs nothing.
  class Contribution
  {
  public:
    virtual ~Contribution() = default;

    virtual std::string name() const = 0;
    virtual ForceKind   kind() const = 0;

    /// Whether add_cell() does anything (the cell loop skips it if not).
    virtual bool has_cell_terms() const = 0;
    /// Adds this cell's share of r to contribution.vector and, if
    /// 'with_tangent', of -dr/d(increment) to contribution.matrix (both
    /// sized 18, kernel DoF order).
    virtual void add_cell(const CellIterator & /*cell*/,
                          const EvaluationPoint & /*point*/,
                          CellContribution & /*contribution*/,
                          bool /*with_tangent*/) const
    {
    }

    /// Adds terms that are not per cell (point and dead loads, which have
    /// no tangent) to the unconstrained residual.
    virtual void add_global(const EvaluationPoint & /*point*/,
                            dealii::Vector<double> & /*residual*/) const
    {
    }

    /// Terms that couple DoFs outside a cell (contact pairs), handed to
    /// 'sink' one block at a time after prepare().
    virtual void add_blocks(const EvaluationPoint & /*point*/,
                            const BlockSink & /*sink*/,
                            bool /*with_tangent*/)
    {
    }

    /// Brings up to date, for the coming solve at 'point', the pairs of
    /// mesh vertices whose translations this contribution may couple
    /// beyond the cells' own (self contact), so that the tangent's pattern
    /// can hold them; returns the list's generation, which changes only
    /// when the list may have (0: no list).
    virtual std::uint64_t
    update_coupled_vertices(const EvaluationPoint & /*point*/) const
    {
      return 0;
    }
    /// Appends the pairs of the last update_coupled_vertices(). A
    /// contribution with such a list overrides both: ShellProblem reads
    /// the lists again only when a generation changed.
    virtual void
    coupled_vertices(std::vector<std::array<unsigned int, 2>> & /*pairs*/) const
    {
    }
    /// Whether add_blocks() may couple vertices of different cells.
    virtual bool couples_beyond_cells() const
    {
      return false;
    }

    /// Called before every evaluation at 'point' (it may move obstacles
    /// towards their position at the point's time, or find contact pairs).
    virtual void prepare(const EvaluationPoint & /*point*/) {}
    /// True while this contribution has not reached the state its time
    /// asks for (an obstacle held back by the step filter): Newton must
    /// not stop then.
    virtual bool pending() const
    {
      return false;
    }
    /// Largest fraction in (0, 1] of 'correction' (DoF layout, from
    /// 'state') that keeps this contribution admissible.
    virtual double admissible_fraction(const ShellState & /*state*/,
                                       const dealii::Vector<double> &
                                       /*correction*/) const
    {
      return 1;
    }
    /// Called at the start of every Newton solve (a load or time step).
    virtual void begin_solve() {}
    /// See NonlinearProblem::extrapolate_reports(): carry what this
    /// contribution reports of the last evaluation along 'correction'.
    virtual void
    extrapolate_reports(const dealii::Vector<double> & /*correction*/)
    {
    }
    /// Keep and go back to internal state along with the configuration.
    virtual void save() {}
    virtual void restore() {}
    /// See NonlinearProblem::begin_trial(): undo what a trial evaluation
    /// changed besides the iterate.
    virtual void begin_trial() {}
    virtual void end_trial() {}

    virtual bool symmetric_tangent() const = 0;

    /// Whether this contribution's force is minus the gradient of the
    /// energy that cell_energy() and global_energy() give (up to what its
    /// class documents), so that a line search may compare energies.
    virtual bool has_potential() const
    {
      return false;
    }
    /// This cell's share of the potential at 'point' (force times length).
    virtual double cell_energy(const CellIterator & /*cell*/,
                               const EvaluationPoint & /*point*/) const
    {
      return 0;
    }
    /// The share that is not per cell (loads, contact pairs): at 'point',
    /// or, for terms made by add_blocks(), at its last call.
    virtual double global_energy(const EvaluationPoint & /*point*/) const
    {
      return 0;
    }

    /// See NonlinearProblem::use_convex_tangent(): switch to a positive
    /// semi-definite tangent until the step is accepted or undone; true if
    /// anything changed.
    virtual bool use_convex_tangent()
    {
      return false;
    }
    /// What a failed solve's message should add about this contribution
    /// (e.g. a shell pinched between obstacles); "" if nothing.
    virtual std::string failure_context() const
    {
      return "";
    }
  };
} // namespace coshell::model
