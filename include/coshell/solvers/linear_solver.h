#pragma once

#include <coshell/base/tangent_matrix.h>

#include <deal.II/base/index_set.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace coshell::solvers
{
  /// Solves K x = b for the assembled (condensed) stiffness. The method is
  /// chosen in prm subsection "Linear solver".
  class LinearSolver
  {
  public:
    LinearSolver();
    ~LinearSolver();

    static void declare_parameters(dealii::ParameterHandler &prm);
    void        parse_parameters(dealii::ParameterHandler &prm);

    /// Factorizes (direct) or sets up the preconditioner (iterative).
    /// 'symmetric' = false makes cholmod fall back to umfpack.
    /// 'release_matrix', when given, is called as soon as the solver no
    /// longer reads 'matrix' (the Trilinos methods, once they hold their own
    /// copy), before the factorization or the AMG hierarchy is built: a
    /// caller that frees its matrix there lowers the peak memory by the
    /// matrix (about 0.5 KB per DoF). Methods that keep reading 'matrix'
    /// never call it.
    void factorize(const dealii::SparseMatrix<double> &matrix,
                   bool                                symmetric       = true,
                   const std::function<void()>        &release_matrix  = {},
                   const std::function<void()>        &complete_matrix = {});
    /// On several ranks: takes over a Trilinos matrix whose rows are
    /// distributed_rows(), assembled by the ranks together, and factorizes
    /// it or sets up its preconditioner; no rank holds the whole matrix.
    void factorize(dealii::TrilinosWrappers::SparseMatrix &&matrix);
    /// A tangent assembled by a base::NonlinearProblem: the deal.II matrix as
    /// above, or the distributed one, which the solver takes over.
    void factorize(base::TangentMatrix &tangent, bool symmetric);
    /// Whether factorize() reads only the entries with column <= row of a
    /// tangent with this symmetry: CHOLMOD's, without kept factors (whose
    /// GMRES multiplies by the whole matrix). A tangent assembled so
    /// (base::TangentMatrix::set_lower_only()) is mirrored if CHOLMOD refuses
    /// it and UMFPACK takes over.
    bool reads_lower_triangle(bool symmetric) const;
    /// The rows this rank holds under mpirun (see set_row_partition); empty
    /// on one rank, where the solvers take complete deal.II matrices.
    const dealii::IndexSet &distributed_rows() const;

    /// How far a direct solve polishes its answer.
    enum class Refinement
    {
      /// UMFPACK's iterative refinement (up to two steps of x += A^-1 (b -
      /// A x)): the answer of a linear analysis.
      iterative,
      /// The factors applied once: a Newton correction, which the next
      /// Newton iteration refines anyway.
      none
    };

    /// Solves with the last matrix given to factorize(). With Reuse
    /// factorization that matrix may not be factorized yet: it is then read
    /// here, so it must be unchanged and alive until the last solve().
    /// Throws std::runtime_error if an iterative method does not converge.
    /// 'refinement' matters to UMFPACK only (CHOLMOD does not refine; the
    /// Trilinos methods solve to their Tolerance).
    void solve(dealii::Vector<double>       &x,
               const dealii::Vector<double> &b,
               Refinement refinement = Refinement::iterative);

    /// Solves once more when the last matrix given to factorize() may be
    /// gone (a time step's tangent, for how the step answers a change of
    /// its data): the direct methods apply their kept factors, which with
    /// Reuse factorization may be those of an earlier matrix; the Trilinos
    /// methods hold their own copy and solve as solve() does.
    void solve_with_factors(dealii::Vector<double>       &x,
                            const dealii::Vector<double> &b);

    /// True when the method can use the near-null space (cg-amg with
    /// "AMG near-null space = rigid body").
    bool uses_near_null_space() const;
    /// Modes the AMG aggregates must represent (the rigid-body motions);
    /// used by the next factorize().
    void set_near_null_space(const std::vector<dealii::Vector<double>> &modes);
    /// Under mpirun: the rows this rank holds (a contiguous range, see
    /// ShellModel::locally_owned_dofs). Matrices and right-hand sides stay
    /// complete on every rank; only this rank's rows go to Trilinos, and
    /// every rank gets the whole solution. Throws std::invalid_argument,
    /// naming the parameter, for a method that runs on one rank only. Does
    /// nothing on one rank.
    void set_row_partition(const dealii::IndexSet &owned_rows);

    /// True for methods that cannot solve a non-symmetric system (cg-amg).
    bool requires_symmetric() const;
    /// Throws std::invalid_argument, naming the parameter, when the method
    /// cannot solve the system described by 'why_not_symmetric' (empty when
    /// the system is symmetric).
    void check_applicable(const std::string &why_not_symmetric) const;

    /// The method in use: "auto" is resolved when the parameters are
    /// parsed (cholmod on one rank, amesos-mumps on several).
    const std::string &method() const;
    /// Iterations of the last solve (1 for a direct solver).
    unsigned int last_iterations() const;
    /// Wall-clock seconds spent in factorize() and solve() so far.
    double seconds() const;
    /// Of seconds(): those spent factorizing (a direct method's copy of
    /// the matrix and its symbolic and numeric factorization, or the AMG
    /// preconditioner's set-up), whether in factorize() or in a solve()
    /// that had to factorize after all. The rest is forward and back
    /// substitution and Krylov iterations.
    double factorization_seconds() const
    {
      return factorization_seconds_;
    }
    /// Factorizations that CHOLMOD refused (not positive definite) and
    /// UMFPACK did instead.
    unsigned int cholmod_fallbacks() const
    {
      return cholmod_fallbacks_;
    }
    /// With "Reuse factorization": numeric factorizations done, and solves
    /// done by GMRES with kept factors instead.
    unsigned int factorizations() const
    {
      return factorizations_;
    }
    unsigned int reused_factor_solves() const
    {
      return reused_factor_solves_;
    }

  private:
    std::string  method_                     = "cholmod";
    double       tolerance_                  = 1e-10;
    unsigned int max_iterations_             = 10000;
    unsigned int last_iterations_            = 0;
    double       seconds_                    = 0;
    double       factorization_seconds_      = 0;
    unsigned int cholmod_fallbacks_          = 0;
    bool         rigid_body_near_null_space_ = true;
    std::string  amg_smoother_               = "Chebyshev";
    unsigned int amg_smoother_sweeps_        = 2;
    double       amg_aggregation_threshold_  = 1e-4;
    bool         reuse_factorization_        = false;
    unsigned int reuse_iterations_           = 10;
    unsigned int factorizations_             = 0;
    unsigned int reused_factor_solves_       = 0;
    /// The matrix factorize() was given but left to GMRES with the kept
    /// factors (reuse), and whether the kept factors are worn out.
    const dealii::SparseMatrix<double> *unfactorized_     = nullptr;
    bool                                factors_worn_out_ = true;
    /// After GMRES with kept factors gave up, that many factorize() calls
    /// factorize without trying them (doubling while attempts keep
    /// failing), so that a run whose matrices jump pays little for trying.
    unsigned int reuse_backoff_ = 0, factorizations_before_retry_ = 0;

    struct Backend;
    std::unique_ptr<Backend> backend_;

    void set_up_trilinos_solver();
    void initialize_amg();
    /// Factorizes 'matrix' now (CHOLMOD if asked for and it succeeds,
    /// UMFPACK otherwise, after 'complete_matrix' if given); its factors
    /// become the kept ones.
    void        factorize_directly(const dealii::SparseMatrix<double> &matrix,
                                   const std::function<void()> &complete_matrix = {});
    bool        solve_with_kept_factors(dealii::Vector<double>       &x,
                                        const dealii::Vector<double> &b);
    bool        is_amesos() const;
    bool        is_amg() const;
    void        solve_krylov(dealii::TrilinosWrappers::MPI::Vector       &x,
                             const dealii::TrilinosWrappers::MPI::Vector &b,
                             double                                       b_norm);
    std::string amesos_solver_name() const;
  };
} // namespace coshell::solvers
