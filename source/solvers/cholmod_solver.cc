#include <coshell/solvers/cholmod_solver.h>

#include "compressed_rows.h"

#include <suitesparse/cholmod.h>

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
    }

    ~Data()
    {
      if (factor)
        cholmod_free_factor(&factor, &common);
      cholmod_finish(&common);
    }

    /// Views the row storage as CHOLMOD's column storage: for a symmetric
    /// matrix row r of A is column r of A. Only entries with row <= column
    /// are read (stype = 1), the columns <= r of row r: only those are
    /// copied.
    void copy(const SparseMatrix<double> &source)
    {
      rows.copy(source, true);
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
  };

  CholmodSolver::CholmodSolver() : data_(std::make_unique<Data>()) {}

  CholmodSolver::~CholmodSolver() = default;

  void CholmodSolver::factorize(const SparseMatrix<double> &matrix)
  {
    Data &d = *data_;
    d.copy(matrix);
    if (!d.factor || !d.rows.same_pattern(d.analysed))
    {
      if (d.factor)
        cholmod_free_factor(&d.factor, &d.common);
      d.factor   = cholmod_analyze(&d.matrix, &d.common);
      d.analysed = d.rows;
    }
    if (!d.factor || !cholmod_factorize(&d.matrix, d.factor, &d.common) ||
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
    Data         &d = *data_;
    cholmod_dense rhs{};
    rhs.nrow = rhs.d = b.size();
    rhs.ncol         = 1;
    rhs.nzmax        = b.size();
    rhs.x            = const_cast<double *>(b.begin());
    rhs.xtype        = CHOLMOD_REAL;
    rhs.dtype        = CHOLMOD_DOUBLE;
    cholmod_dense *solution =
        cholmod_solve(CHOLMOD_A, d.factor, &rhs, &d.common);
    if (!solution)
      throw std::runtime_error("CHOLMOD solve failed (status " +
                               std::to_string(d.common.status) + ")");
    const double *values = static_cast<const double *>(solution->x);
    std::copy(values, values + b.size(), x.begin());
    cholmod_free_dense(&solution, &d.common);
  }
} // namespace coshell::solvers
