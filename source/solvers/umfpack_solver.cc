#include <coshell/solvers/umfpack_solver.h>

#include "compressed_rows.h"

#include <suitesparse/umfpack.h>

#include <stdexcept>
#include <string>

namespace coshell::solvers
{
  using namespace dealii;

  struct UmfpackSolver::Data
  {
    // Row storage of A is column storage of its transpose: UMFPACK factors
    // A^T and solves with the transposed system (UMFPACK_At), giving A x = b.
    CompressedRows matrix, analysed;
    void          *symbolic = nullptr;
    void          *numeric  = nullptr;
    double         control[UMFPACK_CONTROL];
    /// The same with no iterative refinement (apply_factors).
    double control_no_refinement[UMFPACK_CONTROL];

    Data()
    {
      umfpack_di_defaults(control);
      umfpack_di_defaults(control_no_refinement);
      control_no_refinement[UMFPACK_IRSTEP] = 0;
    }

    ~Data()
    {
      free_numeric();
      if (symbolic)
        umfpack_di_free_symbolic(&symbolic);
    }

    void free_numeric()
    {
      if (numeric)
        umfpack_di_free_numeric(&numeric);
    }

    void analyse()
    {
      if (symbolic)
        umfpack_di_free_symbolic(&symbolic);
      const int n      = matrix.n_rows();
      const int status = umfpack_di_symbolic(
          n, n, matrix.starts.data(), matrix.indices.data(),
          matrix.values.data(), &symbolic, control, nullptr);
      check(status, "symbolic analysis");
      analysed = matrix;
    }

    static void check(int status, const std::string &stage)
    {
      if (status == UMFPACK_WARNING_singular_matrix)
        throw std::runtime_error(
            "UMFPACK: the matrix is singular (" + stage +
            "): missing supports, or a structure past a bifurcation");
      if (status != UMFPACK_OK)
        throw std::runtime_error("UMFPACK " + stage + " failed (status " +
                                 std::to_string(status) + ")");
    }
  };

  UmfpackSolver::UmfpackSolver() : data_(std::make_unique<Data>()) {}

  UmfpackSolver::~UmfpackSolver() = default;

  void UmfpackSolver::factorize(const SparseMatrix<double> &matrix)
  {
    Data &d = *data_;
    d.matrix.copy(matrix);
    if (!d.symbolic || !d.matrix.same_pattern(d.analysed))
      d.analyse();
    d.free_numeric();
    const int status = umfpack_di_numeric(
        d.matrix.starts.data(), d.matrix.indices.data(), d.matrix.values.data(),
        d.symbolic, &d.numeric, d.control, nullptr);
    Data::check(status, "numeric factorization");
  }

  void UmfpackSolver::solve(Vector<double> &x, const Vector<double> &b) const
  {
    const Data &d = *data_;
    x.reinit(b.size());
    const int status =
        umfpack_di_solve(UMFPACK_At, d.matrix.starts.data(),
                         d.matrix.indices.data(), d.matrix.values.data(),
                         x.begin(), b.begin(), d.numeric, d.control, nullptr);
    Data::check(status, "solve");
  }

  bool UmfpackSolver::has_factors_of_size(const unsigned int n_rows) const
  {
    const Data &d = *data_;
    return d.numeric && d.matrix.n_rows() == static_cast<int>(n_rows);
  }

  void UmfpackSolver::apply_factors(Vector<double>       &x,
                                    const Vector<double> &b) const
  {
    const Data &d = *data_;
    x.reinit(b.size(), true);
    const int status = umfpack_di_solve(
        UMFPACK_At, d.matrix.starts.data(), d.matrix.indices.data(),
        d.matrix.values.data(), x.begin(), b.begin(), d.numeric,
        d.control_no_refinement, nullptr);
    Data::check(status, "solve with the kept factors");
  }
} // namespace coshell::solvers
