// LinearSolver with kept factors (Linear solver/Reuse factorization): a
// matrix near the factorized one is solved by GMRES with the old factors
// to the direct solve's answer; one far from it is factorized after all.
#include <coshell/solvers/linear_solver.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparsity_pattern.h>

#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

namespace
{
  using namespace dealii;
  using coshell::solvers::LinearSolver;

  /// UMFPACK with the given entries of "Linear solver" (the defaults
  /// otherwise).
  void
  configure(LinearSolver                                           &solver,
            const std::vector<std::pair<std::string, std::string>> &entries)
  {
    ParameterHandler prm;
    LinearSolver::declare_parameters(prm);
    prm.enter_subsection("Linear solver");
    prm.set("Method", "umfpack");
    for (const auto &[name, value] : entries)
      prm.set(name, value);
    prm.leave_subsection();
    solver.parse_parameters(prm);
  }

  void configure(LinearSolver &solver, bool reuse)
  {
    configure(solver, {{"Reuse factorization", reuse ? "true" : "false"},
                       {"Reuse iterations", "10"},
                       {"Tolerance", "1e-12"}});
  }

  /// A non-symmetric tridiagonal matrix (a 1-D convection-diffusion
  /// operator) whose convection is 'convection'.
  struct Tridiagonal
  {
    SparsityPattern      pattern;
    SparseMatrix<double> matrix;

    explicit Tridiagonal(unsigned int n)
    {
      DynamicSparsityPattern dsp(n, n);
      for (unsigned int i = 0; i < n; ++i)
        for (unsigned int j = (i > 0 ? i - 1 : 0); j < std::min(n, i + 2); ++j)
          dsp.add(i, j);
      pattern.copy_from(dsp);
      matrix.reinit(pattern);
    }

    /// The symmetric operator with its diagonal shifted by 'shift':
    /// positive definite for shift >= 0, indefinite far below.
    const SparseMatrix<double> &set_symmetric(double shift)
    {
      set(0.0);
      for (unsigned int i = 0; i < matrix.m(); ++i)
        matrix.add(i, i, shift);
      return matrix;
    }

    const SparseMatrix<double> &set(double convection)
    {
      for (unsigned int i = 0; i < matrix.m(); ++i)
      {
        matrix.set(i, i, 2.0 + 0.01 * i);
        if (i > 0)
          matrix.set(i, i - 1, -1.0 - convection);
        if (i + 1 < matrix.m())
          matrix.set(i, i + 1, -1.0 + convection);
      }
      return matrix;
    }
  };

  Vector<double> direct_solution(const SparseMatrix<double> &matrix,
                                 const Vector<double>       &b)
  {
    LinearSolver direct;
    configure(direct, false);
    direct.factorize(matrix, false);
    Vector<double> x(b.size());
    direct.solve(x, b);
    return x;
  }

  /// |x - the direct solve's answer| <= tolerance |x| (max norms).
  void expect_direct_answer(const SparseMatrix<double> &matrix,
                            const Vector<double>       &b,
                            const Vector<double>       &x,
                            double                      tolerance)
  {
    Vector<double> error = direct_solution(matrix, b);
    error -= x;
    EXPECT_LT(error.linfty_norm(), tolerance * x.linfty_norm());
  }
  /// Factorizes and solves set(0), then set(1) (the same matrix object,
  /// changed); returns the second answer.
  template<typename Set>
  Vector<double> solve_two_matrices(LinearSolver         &solver,
                                    const Set            &set,
                                    const Vector<double> &b,
                                    bool                  symmetric)
  {
    Vector<double> x(b.size());
    for (unsigned int k = 0; k < 2; ++k)
    {
      solver.factorize(set(k), symmetric);
      solver.solve(x, b);
    }
    return x;
  }

  void expect_counts(const LinearSolver &solver,
                     unsigned int        factorizations,
                     unsigned int        reused_solves,
                     unsigned int        fallbacks)
  {
    EXPECT_EQ(solver.factorizations(), factorizations);
    EXPECT_EQ(solver.reused_factor_solves(), reused_solves);
    EXPECT_EQ(solver.cholmod_fallbacks(), fallbacks);
  }

  /// CHOLMOD with kept factors solves the symmetric operator of 'system'
  /// and then the operator with its diagonal shifted by 'shift'; returns
  /// the second answer.
  Vector<double> shifted_after_cholmod(LinearSolver         &solver,
                                       Tridiagonal          &system,
                                       double                shift,
                                       const Vector<double> &b)
  {
    configure(solver, {{"Method", "cholmod"},
                       {"Reuse factorization", "true"},
                       {"Tolerance", "1e-12"}});
    return solve_two_matrices(
        solver,
        [&](unsigned int k) -> auto & {
          return system.set_symmetric(shift * k);
        },
        b, true);
  }
  /// A smooth right-hand side of n entries, 1 + sin(0.1 i).
  Vector<double> smooth_load(unsigned int n)
  {
    Vector<double> b(n);
    for (unsigned int i = 0; i < n; ++i)
      b[i] = 1.0 + std::sin(0.1 * i);
    return b;
  }
} // namespace

TEST(LinearSolverReuse, NearbyMatrixIsSolvedWithTheKeptFactors)
{
  Tridiagonal          system(200);
  const Vector<double> b = smooth_load(200);
  LinearSolver         solver;
  configure(solver, true);
  Vector<double> x(b.size());
  solver.factorize(system.set(0.10), false);
  solver.solve(x, b);
  // 2 % more convection: the kept factors precondition it well.
  const SparseMatrix<double> &nearby = system.set(0.102);
  solver.factorize(nearby, false);
  solver.solve(x, b);
  EXPECT_EQ(solver.factorizations(), 1u);
  EXPECT_EQ(solver.reused_factor_solves(), 1u);
  EXPECT_GT(solver.last_iterations(), 1u);
  // A second right-hand side before the next factorize() must also be
  // solved for the new matrix, not with the old factors alone.
  Vector<double> b2(b.size()), x2(b.size());
  for (unsigned int i = 0; i < b.size(); ++i)
    b2[i] = std::cos(0.05 * i);
  solver.solve(x2, b2);
  expect_direct_answer(nearby, b, x, 1e-9);
  expect_direct_answer(nearby, b2, x2, 1e-9);
}

TEST(LinearSolverReuse, FarMatrixIsFactorizedAfterAll)
{
  Tridiagonal    system(200);
  Vector<double> b(200);
  b = 1.0;
  LinearSolver solver;
  configure(solver, true);
  // Convection of the order of the diffusion: GMRES with the symmetric
  // operator's factors does not get there in 10 iterations.
  const Vector<double> x = solve_two_matrices(
      solver, [&](unsigned int k) -> auto & { return system.set(0.9 * k); }, b,
      false);
  expect_counts(solver, 2, 0, 0);
  expect_direct_answer(system.matrix, b, x, 1e-12);
}

TEST(LinearSolverReuse, OffByDefault)
{
  Tridiagonal    system(50);
  Vector<double> b(50);
  b = 1.0;
  LinearSolver solver;
  configure(solver, {});
  solve_two_matrices(
      solver,
      [&](unsigned int k) -> auto & { return system.set(0.1 + 1e-4 * k); }, b,
      false);
  EXPECT_EQ(solver.reused_factor_solves(), 0u);
}

TEST(LinearSolverReuse, CholmodFactorsAreKeptToo)
{
  Tridiagonal          system(200);
  const Vector<double> b = smooth_load(200);
  LinearSolver         solver;
  // A 1 % stiffer diagonal: GMRES with the first one's Cholesky factors.
  const Vector<double> x = shifted_after_cholmod(solver, system, 0.02, b);
  expect_counts(solver, 1, 1, 0);
  expect_direct_answer(system.matrix, b, x, 1e-10);
}

TEST(LinearSolverReuse, IndefiniteMatrixAfterKeptCholmodFactorsGoesToUmfpack)
{
  Tridiagonal    system(200);
  Vector<double> b(200);
  b = 1.0;
  LinearSolver solver;
  // Shifted by -3.9 the operator is indefinite (by Gershgorin its
  // eigenvalues lie in (-3.9, 2.1)). The old factors do not precondition
  // it, CHOLMOD refuses it, and UMFPACK factorizes it.
  const Vector<double> x = shifted_after_cholmod(solver, system, -3.9, b);
  expect_counts(solver, 2, 0, 1);
  expect_direct_answer(system.matrix, b, x, 1e-10);
}

// A refused matrix is an expected event (UMFPACK takes it, counted in
// summary.json), and CHOLMOD says nothing about it: its messages go to
// standard output, which an --interactive run keeps for the protocol. At
// print level 1 it wrote "CHOLMOD error: matrix not positive definite"
// there for every refusal (488 lines in the IOL scene).
TEST(LinearSolverFallback, CholmodRefusesAnIndefiniteMatrixSilently)
{
  Tridiagonal    system(200);
  Vector<double> b(200), x(200);
  b = 1.0;
  LinearSolver solver;
  configure(solver, {{"Method", "cholmod"}});
  testing::internal::CaptureStdout();
  testing::internal::CaptureStderr();
  solver.factorize(system.set_symmetric(-3.9), true);
  solver.solve(x, b);
  const std::string out = testing::internal::GetCapturedStdout(),
                    err = testing::internal::GetCapturedStderr();
  EXPECT_EQ(solver.cholmod_fallbacks(), 1u);
  EXPECT_EQ(out, "");
  EXPECT_EQ(err, "");
  expect_direct_answer(system.matrix, b, x, 1e-10);
}

// A Newton correction skips UMFPACK's iterative refinement: the factors
// applied once still solve a well-conditioned system to round-off, after
// a fresh factorization as after kept factors gave up.
TEST(LinearSolverRefinement, WithoutRefinementTheFactorsSolveTheSystem)
{
  Tridiagonal                 system(200);
  const SparseMatrix<double> &matrix = system.set(0.3);
  const Vector<double>        b      = smooth_load(200);
  Vector<double>              x(200), residual(200);
  LinearSolver                solver;
  configure(solver, false);
  solver.factorize(matrix, false);
  solver.solve(x, b, LinearSolver::Refinement::none);
  matrix.residual(residual, x, b);
  EXPECT_LT(residual.linfty_norm(), 1e-13 * b.linfty_norm());
  expect_direct_answer(matrix, b, x, 1e-13);
}

// The Trilinos methods copy the matrix; once they hold the copy the caller
// may free its own (LinearStatic does, at millions of DoFs). The solution
// must not depend on the freed matrix, and methods that keep reading the
// caller's matrix (UMFPACK with kept factors) must never ask.
TEST(LinearSolverRelease, TrilinosMethodsLetTheCallerFreeItsMatrix)
{
  for (const std::string method : {"amesos-klu", "gmres-amg"})
  {
    Tridiagonal    system(60);
    Vector<double> b(60), x(60);
    b                             = 1.0;
    const Vector<double> expected = direct_solution(system.set(0.2), b);
    LinearSolver         solver;
    configure(solver, {{"Method", method}, {"Tolerance", "1e-12"}});
    bool released = false;
    solver.factorize(system.matrix, false,
                     [&]
                     {
                       released = true;
                       system.matrix.clear();
                     });
    solver.solve(x, b);
    EXPECT_TRUE(released) << method;
    x -= expected;
    EXPECT_LT(x.linfty_norm(), 1e-9 * expected.linfty_norm()) << method;
  }
}

TEST(LinearSolverRelease, MethodsThatReadTheMatrixLaterNeverRelease)
{
  Tridiagonal    system(60);
  Vector<double> b(60), x(60);
  b = 1.0;
  LinearSolver solver;
  configure(solver, true); // UMFPACK with kept factors
  bool released = false;
  for (const double convection : {0.2, 0.201})
    solver.factorize(system.set(convection), false, [&] { released = true; });
  solver.solve(x, b);
  EXPECT_FALSE(released);
  expect_direct_answer(system.matrix, b, x, 1e-9);
}

// A symmetric tangent assembled below its diagonal only (what CHOLMOD
// reads) is solved as the whole one: by CHOLMOD when it is positive
// definite, and, when CHOLMOD refuses it, by UMFPACK after the lower
// triangle is mirrored onto the upper one.
TEST(LinearSolverLowerTriangle, ATangentAssembledBelowItsDiagonalIsSolvedWhole)
{
  const Vector<double> b = smooth_load(200);
  // Shifted by -3.9 the operator is indefinite (Gershgorin, above).
  for (const double shift : {0.0, -3.9})
  {
    Tridiagonal                  whole(200);
    const SparseMatrix<double>  &matrix = whole.set_symmetric(shift);
    coshell::base::TangentMatrix lower;
    lower.reinit(whole.pattern);
    lower.set_lower_only(true);
    lower.zero();
    for (unsigned int i = 0; i < 200; ++i)
      for (auto e = matrix.begin(i); e != matrix.end(i); ++e)
        if (e->column() <= i)
          lower.serial().set(i, e->column(), e->value());
    LinearSolver solver;
    configure(solver, {{"Method", "cholmod"}});
    ASSERT_TRUE(solver.reads_lower_triangle(true));
    EXPECT_FALSE(solver.reads_lower_triangle(false));
    solver.factorize(lower, true);
    Vector<double> x(200);
    solver.solve(x, b);
    EXPECT_EQ(solver.cholmod_fallbacks(), shift < 0 ? 1u : 0u);
    expect_direct_answer(matrix, b, x, 1e-10);
    // Mirrored only for UMFPACK.
    EXPECT_EQ(lower.serial().el(0, 1), shift < 0 ? matrix.el(1, 0) : 0.0);
  }
}

TEST(LinearSolverLowerTriangle, OnlyCholmodWithoutKeptFactorsReadsIt)
{
  LinearSolver umfpack, kept;
  configure(umfpack, false);
  configure(kept, {{"Method", "cholmod"}, {"Reuse factorization", "true"}});
  EXPECT_FALSE(umfpack.reads_lower_triangle(true));
  EXPECT_FALSE(kept.reads_lower_triangle(true));
  Tridiagonal                  system(10);
  coshell::base::TangentMatrix lower;
  lower.reinit(system.pattern);
  lower.set_lower_only(true);
  lower.zero();
  EXPECT_THROW(umfpack.factorize(lower, true), std::logic_error);
}

// summary.json splits the linear solver's time into factorization and
// the rest: the part must lie within the whole, and a solve with kept
// factors must add nothing to it.
TEST(LinearSolverTiming, FactorizationIsAPartOfTheSolversTime)
{
  Tridiagonal  system(2000);
  LinearSolver solver;
  configure(solver, true);
  double first_factorization = -1;
  solve_two_matrices(
      solver,
      [&](unsigned int k) -> auto & {
        if (k == 1)
          first_factorization = solver.factorization_seconds();
        return system.set(0.1 + 0.002 * k);
      },
      smooth_load(2000), false);
  expect_counts(solver, 1, 1, 0);
  EXPECT_GT(first_factorization, 0.0);
  EXPECT_EQ(solver.factorization_seconds(), first_factorization);
  EXPECT_LT(solver.factorization_seconds(), solver.seconds());
}
