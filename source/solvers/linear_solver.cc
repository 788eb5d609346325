#include <coshell/base/parallel_environment.h>
#include <coshell/base/stopwatch.h>
#include <coshell/solvers/cholmod_solver.h>
#include <coshell/solvers/linear_solver.h>
#include <coshell/solvers/umfpack_solver.h>

#include <deal.II/base/index_set.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/lac/trilinos_index_access.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_solver.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>
#include <deal.II/lac/trilinos_vector.h>

#include <Teuchos_ParameterList.hpp>

#include <algorithm>
#include <chrono>
#include <stdexcept>

namespace coshell::solvers
{
  using namespace dealii;

  /// Whatever each method keeps between factorize() and solve().
  struct LinearSolver::Backend
  {
    UmfpackSolver umfpack;
    CholmodSolver cholmod;
    /// Whether cholmod is asked for (a symmetric matrix), and whose
    /// factors solve() applies.
    bool using_cholmod = false;
    enum class Factors
    {
      none,
      umfpack,
      cholmod
    } kept = Factors::none;
    bool has_factors_of_size(unsigned int n_rows) const
    {
      return (kept == Factors::cholmod &&
              cholmod.has_factors_of_size(n_rows)) ||
             (kept == Factors::umfpack && umfpack.has_factors_of_size(n_rows));
    }
    /// Created on first use: Trilinos objects need MPI running.
    std::unique_ptr<TrilinosWrappers::SparseMatrix>    trilinos_matrix;
    SolverControl                                      direct_control;
    std::unique_ptr<TrilinosWrappers::SolverDirect>    trilinos_direct;
    std::unique_ptr<TrilinosWrappers::PreconditionAMG> amg;
    /// The rows this rank holds (all rows on one rank), and the ranks.
    IndexSet owned_rows;
    MPI_Comm communicator = MPI_COMM_SELF;
    /// Near-null space, mode after mode, full length (ML reads this rank's
    /// rows of it during set-up).
    std::vector<double> null_space_values, owned_null_space_values;
    unsigned int        n_null_space_modes = 0;

    /// The old solver still points to the old matrix (Amesos_Mumps reads
    /// its communicator when destroyed): it goes first, then the matrix.
    void replace_trilinos_matrix(
        std::unique_ptr<TrilinosWrappers::SparseMatrix> matrix)
    {
      trilinos_direct.reset();
      amg.reset();
      trilinos_matrix = std::move(matrix);
    }

    TrilinosWrappers::MPI::Vector to_trilinos(const Vector<double> &v) const
    {
      TrilinosWrappers::MPI::Vector result(owned_rows, communicator);
      for (const auto row : owned_rows)
        result[row] = v[row];
      result.compress(VectorOperation::insert);
      return result;
    }

    /// Every rank gets the whole solution (the state is replicated).
    void gather(const TrilinosWrappers::MPI::Vector &solution,
                Vector<double>                      &x) const
    {
      x = 0;
      for (const auto row : owned_rows)
        x[row] = solution[row];
      base::sum_over_ranks(x);
    }
  };

  namespace
  {
    /// Calls use(row, columns, values) with the entries of each row of this
    /// rank that are not exactly zero.
    template<typename Use>
    void for_each_nonzero_row(const TrilinosWrappers::SparseMatrix &matrix,
                              const Use                            &use)
    {
      const Epetra_CrsMatrix              &entries = matrix.trilinos_matrix();
      std::vector<types::global_dof_index> columns;
      std::vector<double>                  values;
      for (int local_row = 0; local_row < entries.NumMyRows(); ++local_row)
      {
        int     n;
        double *row_values;
        int    *local_columns;
        entries.ExtractMyRowView(local_row, n, row_values, local_columns);
        columns.clear();
        values.clear();
        for (int k = 0; k < n; ++k)
          if (row_values[k] != 0)
          {
            columns.push_back(TrilinosWrappers::global_column_index(
                entries, local_columns[k]));
            values.push_back(row_values[k]);
          }
        use(TrilinosWrappers::global_row_index(entries, local_row), columns,
            values);
      }
    }

    /// A copy of 'matrix' without its entries that are exactly zero. An
    /// assembled pattern holds structural zeros (a flat shell's couplings of
    /// membrane and bending, there for when it bends), and MUMPS and ML
    /// analyse the pattern, so each zero would cost fill and time; copying
    /// a deal.II matrix into Trilinos (drop tolerance 0) drops them alike.
    TrilinosWrappers::SparseMatrix
    without_zeros(const TrilinosWrappers::SparseMatrix &matrix)
    {
      TrilinosWrappers::SparsityPattern pattern(
          matrix.locally_owned_range_indices(),
          matrix.locally_owned_domain_indices(), matrix.get_mpi_communicator());
      for_each_nonzero_row(
          matrix, [&](auto row, const auto &columns, const auto &)
          { pattern.add_entries(row, columns.begin(), columns.end(), true); });
      pattern.compress();
      TrilinosWrappers::SparseMatrix copy;
      copy.reinit(pattern);
      for_each_nonzero_row(
          matrix, [&](auto row, const auto &columns, const auto &values)
          { copy.set(row, columns, values); });
      copy.compress(VectorOperation::insert);
      return copy;
    }

    /// The method "auto" stands for: the fastest direct solver that runs
    /// with this many ranks. MPI is running by now when mpirun started
    /// the process (main() starts it first), so distributed() is valid.
    std::string resolved_method(const std::string &method)
    {
      if (method != "auto")
        return method;
      return base::distributed() ? "amesos-mumps" : "cholmod";
    }
  } // namespace

  LinearSolver::LinearSolver() : backend_(std::make_unique<Backend>()) {}

  LinearSolver::~LinearSolver() = default;

  void LinearSolver::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Linear solver");
    prm.declare_entry(
        "Method", "auto",
        Patterns::Selection(
            "auto|cholmod|umfpack|amesos-klu|amesos-mumps|cg-amg|gmres-amg"),
        "Selects the linear solver. "
        "auto: cholmod on one rank, amesos-mumps under mpirun on several "
        "ranks (summary.json names the method used); "
        "cholmod: SuiteSparse supernodal Cholesky, analysed "
        "once per sparsity pattern (symmetric positive "
        "definite systems; non-symmetric ones, such as the "
        "consistent co-rotational tangent, fall back to "
        "umfpack); "
        "umfpack: SuiteSparse UMFPACK sparse LU, analysed once per "
        "sparsity pattern; "
        "amesos-klu, amesos-mumps: Trilinos Amesos with KLU or "
        "MUMPS (direct; MUMPS is the route to distributed solves); "
        "cg-amg: conjugate gradients with Trilinos ML algebraic "
        "multigrid (see the AMG entries; slow on thin shells "
        "without the rigid-body near-null space); "
        "gmres-amg: GMRES with the same preconditioner, for "
        "non-symmetric systems. Under mpirun only auto and the "
        "Trilinos methods run (distributed matrix, one block of rows "
        "per rank); amesos-mumps, which auto takes there, is the "
        "distributed direct solver.");
    prm.declare_entry("Tolerance", "1e-10", Patterns::Double(0),
                      "Relative residual tolerance of iterative methods "
                      "(|r| <= tol |b|). Unit: dimensionless.");
    prm.declare_entry("Maximum iterations", "10000", Patterns::Integer(1),
                      "Iteration limit of iterative methods. Unit: "
                      "dimensionless (a count).");
    prm.declare_entry(
        "Reuse factorization", "false", Patterns::Bool(),
        "umfpack and cholmod: keep the factors (LU or Cholesky) of an "
        "earlier matrix and solve a new matrix of the same size by GMRES "
        "(right preconditioned, to 'Tolerance') with them, refactoring "
        "only when GMRES needs more than 'Reuse iterations', or needed "
        "more than half of them the time before. For sequences of nearby "
        "matrices: the Newton iterations of a step, consecutive time "
        "steps. Off: every matrix is factorized.");
    prm.declare_entry("Reuse iterations", "10", Patterns::Integer(1),
                      "GMRES iterations allowed with kept factors before "
                      "the matrix is factorized. Unit: dimensionless (a "
                      "count).");
    prm.declare_entry("AMG near-null space", "rigid body",
                      Patterns::Selection("rigid body|none"),
                      "Selects the AMG near-null space. "
                      "rigid body: give ML the six rigid-body motions "
                      "(translations and rotations, with the rotation DoFs) "
                      "as the near-null space, 6 DoFs per node; none: ML's "
                      "default (one constant per DoF), which ignores the "
                      "coupling of translations and rotations.");
    prm.declare_entry(
        "AMG smoother", "Chebyshev",
        Patterns::Selection("Chebyshev|symmetric Gauss-Seidel|ILU"),
        "Selects the ML smoother type (Chebyshev, symmetric "
        "Gauss-Seidel or ILU).");
    prm.declare_entry("AMG smoother sweeps", "2", Patterns::Integer(1),
                      "Smoothing sweeps per level. Unit: dimensionless (a "
                      "count).");
    prm.declare_entry("AMG aggregation threshold", "1e-4", Patterns::Double(0),
                      "ML aggregation threshold (drop tolerance of the "
                      "strength-of-connection graph). Unit: "
                      "dimensionless.");
    prm.leave_subsection();
  }

  void LinearSolver::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Linear solver");
    method_         = resolved_method(prm.get("Method"));
    tolerance_      = prm.get_double("Tolerance");
    max_iterations_ = prm.get_integer("Maximum iterations");
    rigid_body_near_null_space_ =
        prm.get("AMG near-null space") == "rigid body";
    amg_smoother_              = prm.get("AMG smoother");
    amg_smoother_sweeps_       = prm.get_integer("AMG smoother sweeps");
    amg_aggregation_threshold_ = prm.get_double("AMG aggregation threshold");
    reuse_factorization_       = prm.get_bool("Reuse factorization");
    reuse_iterations_          = prm.get_integer("Reuse iterations");
    prm.leave_subsection();
  }

  double LinearSolver::seconds() const
  {
    return seconds_;
  }

  void LinearSolver::factorize(const SparseMatrix<double>  &matrix,
                               bool                         symmetric,
                               const std::function<void()> &release_matrix,
                               const std::function<void()> &complete_matrix)
  {
    const base::Stopwatch timer(seconds_);
    backend_->using_cholmod = method_ == "cholmod" && symmetric;
    if (method_ == "umfpack" || method_ == "cholmod")
    {
      unfactorized_ = nullptr;
      // Any kept factors precondition the new matrix, CHOLMOD's or
      // UMFPACK's: GMRES only needs them near its inverse.
      if (reuse_factorization_ && !factors_worn_out_ &&
          factorizations_before_retry_ == 0 &&
          backend_->has_factors_of_size(matrix.m()))
      {
        unfactorized_ = &matrix;
        return;
      }
      if (factorizations_before_retry_ > 0)
        --factorizations_before_retry_;
      factorize_directly(matrix, complete_matrix);
      return;
    }
    base::ensure_mpi_initialized();
    if (backend_->owned_rows.size() != matrix.m())
    {
      backend_->owned_rows   = complete_index_set(matrix.m());
      backend_->communicator = MPI_COMM_SELF;
    }
    backend_->replace_trilinos_matrix(
        std::make_unique<TrilinosWrappers::SparseMatrix>());
    // Drop nothing: mass terms in t/mm^3 are far below Trilinos' default
    // drop tolerance of 1e-13.
    backend_->trilinos_matrix->reinit(backend_->owned_rows,
                                      backend_->owned_rows, matrix,
                                      backend_->communicator, 0.0);
    if (release_matrix)
      release_matrix();
    set_up_trilinos_solver();
  }

  void
  LinearSolver::factorize_directly(const SparseMatrix<double>  &matrix,
                                   const std::function<void()> &complete_matrix)
  {
    const base::Stopwatch timer(factorization_seconds_);
    ++factorizations_;
    factors_worn_out_ = false;
    if (backend_->using_cholmod)
    {
      // A symmetric tangent need not be positive definite (past a limit
      // point, or the symmetrized co-rotational tangent under compression):
      // then this factorization is UMFPACK's.
      try
      {
        backend_->cholmod.factorize(matrix);
        backend_->kept = Backend::Factors::cholmod;
        return;
      }
      catch (const std::runtime_error &)
      {
        backend_->using_cholmod = false;
        ++cholmod_fallbacks_;
      }
    }
    if (complete_matrix)
      complete_matrix();
    backend_->kept = Backend::Factors::none;
    backend_->umfpack.factorize(matrix);
    backend_->kept = Backend::Factors::umfpack;
  }

  void LinearSolver::factorize(TrilinosWrappers::SparseMatrix &&matrix)
  {
    const base::Stopwatch timer(seconds_);
    AssertThrow(base::distributed() && matrix.locally_owned_range_indices() ==
                                           backend_->owned_rows,
                ExcMessage("a distributed matrix needs the rows of "
                           "set_row_partition()"));
    backend_->using_cholmod = false;
    unfactorized_           = nullptr;
    // The old factors go before the copy is made, the assembled matrix
    // right after.
    backend_->replace_trilinos_matrix(nullptr);
    auto kept =
        std::make_unique<TrilinosWrappers::SparseMatrix>(without_zeros(matrix));
    matrix.clear();
    backend_->replace_trilinos_matrix(std::move(kept));
    set_up_trilinos_solver();
  }

  void LinearSolver::factorize(base::TangentMatrix &tangent, bool symmetric)
  {
    if (tangent.distributed())
      factorize(tangent.take_trilinos());
    else if (tangent.lower_only())
    {
      if (!reads_lower_triangle(symmetric))
        throw std::logic_error("LinearSolver: a tangent assembled below its "
                               "diagonal only, for a solver that reads it "
                               "whole");
      factorize(tangent.serial(), symmetric, {},
                [&tangent] { tangent.mirror_lower(); });
    }
    else
      factorize(tangent.serial(), symmetric);
  }

  bool LinearSolver::reads_lower_triangle(bool symmetric) const
  {
    return method_ == "cholmod" && symmetric && !reuse_factorization_ &&
           !base::distributed();
  }

  const IndexSet &LinearSolver::distributed_rows() const
  {
    static const IndexSet none;
    return base::distributed() ? backend_->owned_rows : none;
  }

  void LinearSolver::set_up_trilinos_solver()
  {
    const base::Stopwatch timer(factorization_seconds_);
    if (is_amesos())
    {
      backend_->trilinos_direct =
          std::make_unique<TrilinosWrappers::SolverDirect>(
              backend_->direct_control,
              TrilinosWrappers::SolverDirect::AdditionalData(
                  false, amesos_solver_name()));
      backend_->trilinos_direct->initialize(*backend_->trilinos_matrix);
    }
    else
      initialize_amg();
  }

  void LinearSolver::initialize_amg()
  {
    TrilinosWrappers::PreconditionAMG::AdditionalData data;
    data.elliptic              = true;
    data.smoother_type         = amg_smoother_.c_str();
    data.smoother_sweeps       = amg_smoother_sweeps_;
    data.aggregation_threshold = amg_aggregation_threshold_;
    Teuchos::ParameterList              parameters;
    std::unique_ptr<Epetra_MultiVector> unused_constant_modes;
    data.set_parameters(parameters, unused_constant_modes,
                        *backend_->trilinos_matrix);
    if (uses_near_null_space() && backend_->n_null_space_modes > 0)
    {
      // Blocks of 6 consecutive DoFs per vertex (deal.II's numbering of a
      // vertex-only FESystem), so ML aggregates nodes, not single DoFs.
      parameters.set("PDE equations", 6);
      parameters.set("null space: type", "pre-computed");
      parameters.set("null space: dimension",
                     static_cast<int>(backend_->n_null_space_modes));
      // ML reads the rows of this rank, mode after mode; on one rank those
      // are all rows, and a copy would only cost 48 bytes per DoF.
      auto      &all   = backend_->null_space_values;
      auto      &owned = backend_->owned_null_space_values;
      const auto n     = all.size() / backend_->n_null_space_modes;
      owned.clear();
      const bool all_rows = backend_->owned_rows.n_elements() == n;
      if (!all_rows)
        for (unsigned int mode = 0; mode < backend_->n_null_space_modes; ++mode)
          for (const auto row : backend_->owned_rows)
            owned.push_back(all[mode * n + row]);
      parameters.set("null space: vectors",
                     all_rows ? all.data() : owned.data());
    }
    backend_->amg = std::make_unique<TrilinosWrappers::PreconditionAMG>();
    backend_->amg->initialize(*backend_->trilinos_matrix, parameters);
  }

  bool LinearSolver::is_amesos() const
  {
    return method_.rfind("amesos-", 0) == 0;
  }

  std::string LinearSolver::amesos_solver_name() const
  {
    return method_ == "amesos-mumps" ? "Amesos_Mumps" : "Amesos_Klu";
  }

  bool LinearSolver::uses_near_null_space() const
  {
    return is_amg() && rigid_body_near_null_space_;
  }

  bool LinearSolver::is_amg() const
  {
    return method_ == "cg-amg" || method_ == "gmres-amg";
  }

  void LinearSolver::set_row_partition(const IndexSet &owned_rows)
  {
    if (!base::distributed())
    {
      backend_->owned_rows.clear();
      return;
    }
    if (method_ == "cholmod" || method_ == "umfpack")
      throw std::invalid_argument(
          "Linear solver/Method = " + method_ + " runs on one rank, but " +
          std::to_string(base::n_ranks()) +
          " MPI ranks share this run; choose amesos-mumps (distributed "
          "direct), amesos-klu (gathered on one rank), cg-amg or gmres-amg");
    backend_->owned_rows   = owned_rows;
    backend_->communicator = MPI_COMM_WORLD;
  }

  void
  LinearSolver::set_near_null_space(const std::vector<Vector<double>> &modes)
  {
    backend_->n_null_space_modes = modes.size();
    backend_->null_space_values.clear();
    for (const auto &mode : modes)
      backend_->null_space_values.insert(backend_->null_space_values.end(),
                                         mode.begin(), mode.end());
  }

  void LinearSolver::solve(Vector<double>       &x,
                           const Vector<double> &b,
                           Refinement            refinement)
  {
    const base::Stopwatch timer(seconds_);
    if (method_ == "umfpack" || method_ == "cholmod")
    {
      if (unfactorized_ && solve_with_kept_factors(x, b))
        return;
      if (unfactorized_) // GMRES gave up: factorize after all
      {
        factorize_directly(*unfactorized_);
        unfactorized_ = nullptr;
      }
      if (backend_->kept == Backend::Factors::cholmod)
        backend_->cholmod.solve(x, b);
      else if (refinement == Refinement::none)
        backend_->umfpack.apply_factors(x, b);
      else
        backend_->umfpack.solve(x, b);
      last_iterations_ = 1;
      return;
    }
    const TrilinosWrappers::MPI::Vector rhs = backend_->to_trilinos(b);
    TrilinosWrappers::MPI::Vector       solution(backend_->owned_rows,
                                                 backend_->communicator);
    if (is_amesos())
    {
      backend_->trilinos_direct->solve(solution, rhs);
      last_iterations_ = 1;
    }
    else
      solve_krylov(solution, rhs, b.l2_norm());
    backend_->gather(solution, x);
  }

  void LinearSolver::solve_with_factors(Vector<double>       &x,
                                        const Vector<double> &b)
  {
    if (method_ != "umfpack" && method_ != "cholmod")
      return solve(x, b);
    const base::Stopwatch timer(seconds_);
    x.reinit(b.size());
    if (backend_->kept == Backend::Factors::none)
      throw std::logic_error("solve_with_factors: nothing was factorized");
    if (backend_->kept == Backend::Factors::cholmod)
      backend_->cholmod.solve(x, b);
    else
      backend_->umfpack.apply_factors(x, b);
  }

  namespace
  {
    /// The kept factors (CHOLMOD's or UMFPACK's) as a deal.II
    /// preconditioner.
    struct KeptFactors
    {
      const UmfpackSolver &umfpack;
      const CholmodSolver *cholmod; ///< null: UMFPACK's factors
      void vmult(Vector<double> &x, const Vector<double> &b) const
      {
        if (cholmod)
          cholmod->solve(x, b);
        else
          umfpack.apply_factors(x, b);
      }
    };
  } // namespace

  bool LinearSolver::solve_with_kept_factors(Vector<double>       &x,
                                             const Vector<double> &b)
  {
    // Right preconditioning, so that GMRES measures the true residual
    // |b - A x| against the tolerance, as a direct solve would meet it.
    SolverControl control(reuse_iterations_, tolerance_ * b.l2_norm(), false,
                          false);
    SolverGMRES<Vector<double>>::AdditionalData gmres(reuse_iterations_ + 2,
                                                      true);
    x.reinit(b.size());
    try
    {
      SolverGMRES<Vector<double>>(control, gmres)
          .solve(*unfactorized_, x, b,
                 KeptFactors{backend_->umfpack,
                             backend_->kept == Backend::Factors::cholmod
                                 ? &backend_->cholmod
                                 : nullptr});
    }
    catch (const SolverControl::NoConvergence &)
    {
      factors_worn_out_            = true;
      reuse_backoff_               = std::min(2 * reuse_backoff_ + 1, 32u);
      factorizations_before_retry_ = reuse_backoff_;
      return false;
    }
    reuse_backoff_   = 0;
    last_iterations_ = control.last_step();
    // Factors that needed more than half the allowance will soon fail:
    // the next matrix is factorized instead of tried first.
    factors_worn_out_ = 2 * control.last_step() > reuse_iterations_;
    ++reused_factor_solves_;
    return true;
  }

  void LinearSolver::solve_krylov(TrilinosWrappers::MPI::Vector       &x,
                                  const TrilinosWrappers::MPI::Vector &b,
                                  double                               b_norm)
  {
    SolverControl control(max_iterations_, tolerance_ * b_norm);
    try
    {
      if (method_ == "cg-amg")
        SolverCG<TrilinosWrappers::MPI::Vector>(control).solve(
            *backend_->trilinos_matrix, x, b, *backend_->amg);
      else
        SolverGMRES<TrilinosWrappers::MPI::Vector>(control).solve(
            *backend_->trilinos_matrix, x, b, *backend_->amg);
    }
    catch (const SolverControl::NoConvergence &failure)
    {
      throw std::runtime_error(
          "Linear solver/Method = " + method_ + " did not converge in " +
          std::to_string(failure.last_step) + " iterations (residual " +
          std::to_string(failure.last_residual) + ")");
    }
    last_iterations_ = control.last_step();
  }

  bool LinearSolver::requires_symmetric() const
  {
    return method_ == "cg-amg";
  }

  void
  LinearSolver::check_applicable(const std::string &why_not_symmetric) const
  {
    if (requires_symmetric() && !why_not_symmetric.empty())
      throw std::invalid_argument(
          "Linear solver/Method = " + method_ +
          " (conjugate gradients) needs a symmetric matrix, but " +
          why_not_symmetric +
          " is not symmetric; choose cholmod (which falls back to umfpack "
          "for non-symmetric matrices), umfpack, amesos-klu or amesos-mumps");
  }

  const std::string &LinearSolver::method() const
  {
    return method_;
  }

  unsigned int LinearSolver::last_iterations() const
  {
    return last_iterations_;
  }
} // namespace coshell::solvers
