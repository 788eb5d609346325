#include <coshell/solvers/cholmod_solver.h>

#include <suitesparse/cholmod.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace coshell::solvers
{
  using namespace dealii;

  struct CholmodSolver::Data
  {
    cholmod_common   common;
    cholmod_factor  *factor = nullptr;
    std::vector<int> column_starts, row_indices;
    /// The pattern the symbolic factorization was computed for.
    std::vector<int>    analysed_starts, analysed_indices;
    std::vector<double> values;
    cholmod_sparse      matrix{};

    Data()
    {
      cholmod_start(&common);
    }

    ~Data()
    {
      if (factor)
        cholmod_free_factor(&factor, &common);
      cholmod_finish(&common);
    }

    /// Views deal.II's CSR storage as CHOLMOD's CSC: for a symmetric matrix
    /// row r of A is column r of A. Only entries with row <= column are
    /// read (stype = 1).
    void copy(const SparseMatrix<double> &source)
    {
      const SparsityPattern &sp = source.get_sparsity_pattern();
      const unsigned int     n  = sp.n_rows();
      column_starts.assign(n + 1, 0);
      row_indices.resize(sp.n_nonzero_elements());
      values.resize(sp.n_nonzero_elements());
      unsigned int k = 0;
      for (unsigned int r = 0; r < n; ++r)
      {
        column_starts[r] = k;
        for (auto entry = source.begin(r); entry != source.end(r); ++entry, ++k)
        {
          row_indices[k] = entry->column();
          values[k]      = entry->value();
        }
      }
      column_starts[n] = k;
      matrix.nrow = matrix.ncol = n;
      matrix.nzmax              = k;
      matrix.p                  = column_starts.data();
      matrix.i                  = row_indices.data();
      matrix.x                  = values.data();
      matrix.stype              = 1;
      matrix.itype              = CHOLMOD_INT;
      matrix.xtype              = CHOLMOD_REAL;
      matrix.dtype              = CHOLMOD_DOUBLE;
      matrix.sorted             = false;
      matrix.packed             = true;
    }
  };

  CholmodSolver::CholmodSolver() : data_(std::make_unique<Data>()) {}

  CholmodSolver::~CholmodSolver() = default;

  void CholmodSolver::factorize(const SparseMatrix<double> &matrix)
  {
    Data &d = *data_;
    d.copy(matrix);
    if (!d.factor || d.column_starts != d.analysed_starts ||
        d.row_indices != d.analysed_indices)
    {
      if (d.factor)
        cholmod_free_factor(&d.factor, &d.common);
      d.factor           = cholmod_analyze(&d.matrix, &d.common);
      d.analysed_starts  = d.column_starts;
      d.analysed_indices = d.row_indices;
    }
    if (!d.factor || !cholmod_factorize(&d.matrix, d.factor, &d.common) ||
        d.common.status == CHOLMOD_NOT_POSDEF)
      throw std::runtime_error(
          "CHOLMOD could not factorize the stiffness matrix (status " +
          std::to_string(d.common.status) +
          "): it is not symmetric positive definite. Use Linear solver/"
          "Method = umfpack for indefinite or non-symmetric systems.");
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
      throw std::runtime_error("CHOLMOD solve failed");
    const double *values = static_cast<const double *>(solution->x);
    std::copy(values, values + b.size(), x.begin());
    cholmod_free_dense(&solution, &d.common);
  }
} // namespace coshell::solvers
