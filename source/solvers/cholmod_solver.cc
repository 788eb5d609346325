#include <coshell/base/parallel_environment.h>
#include <coshell/solvers/cholmod_solver.h>

#include "compressed_rows.h"

#include <suitesparse/cholmod.h>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

namespace coshell::solvers
{
  using namespace dealii;

  struct CholmodSolver::Data
  {
    cholmod_common  common;
    cholmod_factor *factor = nullptr;
    /// The matrix and the pattern the symbolic factorization was computed
    /// for.
    CompressedRows rows, analysed;
    cholmod_sparse matrix{};
    /// The lower triangle of the permuted matrix P A P', in compressed
    /// columns (CHOLMOD's own layout); `factor` is its Cholesky factor in
    /// the natural order. Each entry of it is rows.values[source[entry]].
    cholmod_sparse  *permuted = nullptr;
    std::vector<int> source;
    /// The fill-reducing order: row k of P A P' is row order[k] of A.
    std::vector<int> order;
    /// The factorization's floating-point operations, from the analysis.
    double flops = 0;
    /// Kept between solves: the permuted right-hand side, the solution
    /// and CHOLMOD's workspaces.
    cholmod_dense *rhs = nullptr, *solution = nullptr, *work_y = nullptr,
                  *work_e = nullptr;

    Data()
    {
      cholmod_start(&common);
      // A small matrix gets CHOLMOD's simplicial factorization, by default
      // LDL', which accepts an indefinite matrix without a word and, with
      // no pivoting, can lose accuracy (a shifted 200 x 200 tridiagonal:
      // 0.3 % error). LL' reports a non-positive pivot as the supernodal
      // factorization does, and the caller goes to UMFPACK.
      common.final_ll = true;
      // Silent: CHOLMOD prints with printf, on standard output, which an
      // --interactive run keeps for its protocol. A matrix that is not
      // positive definite is an expected event here (the caller goes to
      // UMFPACK and counts it in summary.json's cholmod_fallbacks); below
      // level 2 CHOLMOD prints that warning as "CHOLMOD error", 488 lines
      // in the IOL scene. Real failures reach the caller as its status.
      common.print = 0;
      // Relaxed amalgamation: CHOLMOD merges two adjacent supernodes when
      // that adds no zero, or the merged one has at most nrelax[0]
      // columns, or at most nrelax[1] and under zrelax[0] = 80 % zeros,
      // or at most nrelax[2] and under 10 %, or under 5 % at any size.
      // A shell vertex has six DoFs: CHOLMOD's defaults 4, 16 and 48
      // leave vertices apart that 6, 24 (four vertices) and 72 merge.
      // Fewer, larger supernodes cost a few more flops and far fewer
      // small BLAS calls, so the factorizations of shells of a few
      // thousand DoFs take less time (doc/performance/scaling.md).
      common.nrelax[0] = 6;
      common.nrelax[1] = 24;
      common.nrelax[2] = 72;
    }

    ~Data()
    {
      if (factor)
        cholmod_free_factor(&factor, &common);
      for (cholmod_dense **dense : {&rhs, &solution, &work_y, &work_e})
        cholmod_free_dense(dense, &common);
      cholmod_free_sparse(&permuted, &common);
      cholmod_finish(&common);
    }

    /// Views the row storage as CHOLMOD's column storage: for a symmetric
    /// matrix row r of A is column r of A. Only entries with row <= column
    /// are read (stype = 1), the columns <= r of row r: only those are
    /// copied.
    void copy(const SparseMatrix<double> &source_matrix)
    {
      rows.copy(source_matrix, true);
      matrix.nrow = matrix.ncol = rows.n_rows();
      matrix.nzmax              = rows.values.size();
      matrix.p                  = rows.starts.data();
      matrix.i                  = rows.indices.data();
      matrix.x                  = rows.values.data();
      matrix.stype              = 1;
      matrix.itype              = CHOLMOD_INT;
      matrix.xtype              = CHOLMOD_REAL;
      matrix.dtype              = CHOLMOD_DOUBLE;
      matrix.sorted             = true;
      matrix.packed             = true;
    }

    void analyse();
    void permute_values();
  };

  /// Orders the matrix (CHOLMOD's default choice, AMD or METIS,
  /// postordered), then analyses P A P' again in the natural order, given
  /// explicitly as its lower triangle: a supernodal factorization reads
  /// that as it is. Given A's upper triangle and P, CHOLMOD built
  /// tril(P A P') itself at every factorization, a noticeable part of a
  /// small factorization's time. Here the map from A's entries to
  /// those of P A P' is made once per pattern: a transposition of the
  /// entries' own positions. (A matrix small enough for a simplicial
  /// factor is still transposed once per factorization, by CHOLMOD.)
  void CholmodSolver::Data::analyse()
  {
    if (factor)
      cholmod_free_factor(&factor, &common);
    cholmod_free_sparse(&permuted, &common);
    // Made before CHOLMOD allocates: nothing below throws while it holds
    // memory of its own.
    std::vector<double> positions(rows.values.size());
    for (std::size_t k = 0; k < positions.size(); ++k)
      positions[k] = static_cast<double>(k);
    order.resize(rows.n_rows());
    // The order only: the simplicial analysis stops before the supernodes,
    // which the second analysis finds (cheaper than two supernodal
    // analyses).
    const int kind           = common.supernodal;
    common.supernodal        = CHOLMOD_SIMPLICIAL;
    cholmod_factor *ordering = cholmod_analyze(&matrix, &common);
    common.supernodal        = kind;
    if (!ordering)
      return;
    const int *perm = static_cast<const int *>(ordering->Perm);
    std::copy(perm, perm + order.size(), order.begin());
    cholmod_sparse entries = matrix;
    entries.x              = positions.data();
    permuted               = cholmod_ptranspose(
                      &entries, 2, static_cast<int *>(ordering->Perm), nullptr, 0, &common);
    cholmod_free_factor(&ordering, &common);
    if (!permuted)
      return;
    const double *from = static_cast<const double *>(permuted->x);
    source.assign(from, from + cholmod_nnz(permuted, &common));
    const int methods = common.nmethods, post = common.postorder,
              first           = common.method[0].ordering;
    common.nmethods           = 1;
    common.method[0].ordering = CHOLMOD_NATURAL;
    common.postorder          = false; // already postordered
    factor                    = cholmod_analyze(permuted, &common);
    flops                     = common.fl;
    common.nmethods           = methods;
    common.method[0].ordering = first;
    common.postorder          = post;
    analysed                  = rows;
  }

  void CholmodSolver::Data::permute_values()
  {
    double       *to   = static_cast<double *>(permuted->x);
    const double *from = rows.values.data();
    for (std::size_t k = 0; k < source.size(); ++k)
      to[k] = from[source[k]];
  }

  CholmodSolver::CholmodSolver() : data_(std::make_unique<Data>()) {}

  CholmodSolver::~CholmodSolver() = default;

  void CholmodSolver::factorize(const SparseMatrix<double> &matrix)
  {
    Data &d = *data_;
    d.copy(matrix);
    if (!d.factor || !d.rows.same_pattern(d.analysed))
      d.analyse();
    if (d.factor)
      d.permute_values();
    // OpenBLAS shares a call between threads by its size alone, and the
    // supernodes of a small factorization make calls it shares at a loss:
    // the IOL's haptic step factorizes faster on one BLAS thread than on
    // two. A clamped plate of half a million DoFs solves no faster on two
    // either, but larger machines may: the line is drawn low
    // (doc/performance/scaling.md).
    constexpr double       smallest_shared_flops = 1e8;
    const base::SerialBlas serial(d.flops < smallest_shared_flops);
    if (!d.factor || !cholmod_factorize(d.permuted, d.factor, &d.common) ||
        d.common.status == CHOLMOD_NOT_POSDEF)
      throw std::runtime_error(
          "CHOLMOD could not factorize the stiffness matrix (status " +
          std::to_string(d.common.status) + "): " +
          (d.common.status == CHOLMOD_NOT_POSDEF
               ? "it is not symmetric positive definite. Use Linear solver/"
                 "Method = umfpack for indefinite or non-symmetric systems."
           : d.common.status == CHOLMOD_OUT_OF_MEMORY
               ? "out of memory."
               : "an error of CHOLMOD's (cholmod.h lists its codes)."));
  }

  bool CholmodSolver::has_factors_of_size(const unsigned int n_rows) const
  {
    const cholmod_factor *factor = data_->factor;
    // 'minor' is the column where a failed factorization stopped, n after
    // a successful one.
    return factor && factor->n == n_rows && factor->minor == n_rows;
  }

  void CholmodSolver::solve(Vector<double> &x, const Vector<double> &b) const
  {
    Data              &d = *data_;
    const unsigned int n = b.size();
    if (!d.factor || d.factor->n != n)
      throw std::logic_error("CHOLMOD solve without the factors of a " +
                             std::to_string(n) + " x " + std::to_string(n) +
                             " matrix");
    if (!d.rhs || d.rhs->nrow != n)
    {
      cholmod_free_dense(&d.rhs, &d.common);
      d.rhs = cholmod_allocate_dense(n, 1, n, CHOLMOD_REAL, &d.common);
      if (!d.rhs)
        throw std::runtime_error("CHOLMOD solve: out of memory");
    }
    double *permuted_b = static_cast<double *>(d.rhs->x);
    for (unsigned int k = 0; k < n; ++k)
      permuted_b[k] = b[d.order[k]];
    if (!cholmod_solve2(CHOLMOD_A, d.factor, d.rhs, nullptr, &d.solution,
                        nullptr, &d.work_y, &d.work_e, &d.common))
      throw std::runtime_error("CHOLMOD solve failed (status " +
                               std::to_string(d.common.status) + ")");
    const double *y = static_cast<const double *>(d.solution->x);
    for (unsigned int k = 0; k < n; ++k)
      x[d.order[k]] = y[k];
  }
} // namespace coshell::solvers
