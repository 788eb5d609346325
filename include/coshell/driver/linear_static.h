#pragma once

#include <coshell/model/loads.h>
#include <coshell/model/shell_model.h>
#include <coshell/solvers/linear_solver.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>

#include <memory>
#include <ostream>

namespace coshell::driver
{
  /// Small-displacement static analysis: K u = f with constraints.
  class LinearStatic
  {
  public:
    /// With 'distributed_rows' (LinearSolver::distributed_rows() under
    /// mpirun) K is a Trilinos matrix of which this rank assembles its
    /// cells and holds those rows; otherwise a deal.II matrix, complete on
    /// every rank.
    LinearStatic(const model::ShellModel                 &model,
                 const dealii::AffineConstraints<double> &constraints,
                 const dealii::IndexSet &distributed_rows = {});

    /// Assembles K and f. DoFs that no element stiffens (the in-plane DoFs
    /// of a flat plate with the membrane off) get a unit-scaled diagonal so
    /// K stays regular; a load on such a DoF is an error.
    void assemble(const model::Loads &loads, std::ostream &log);

    /// Factorizes and solves; returns the displacement/rotation vector.
    /// K is released once the solver holds its own copy (the Trilinos
    /// methods); the next assemble() allocates it again.
    dealii::Vector<double> solve(solvers::LinearSolver &solver);

    unsigned int n_inactive_dofs() const;

  private:
    const model::ShellModel                 &model_;
    const dealii::AffineConstraints<double> &constraints_;
    dealii::IndexSet                         distributed_rows_;
    dealii::SparsityPattern                  sparsity_;
    dealii::SparseMatrix<double>             stiffness_;
    /// Under mpirun only: a Trilinos object starts talking to MPI when built.
    std::unique_ptr<dealii::TrilinosWrappers::SparseMatrix>
                           distributed_stiffness_;
    dealii::Vector<double> load_;
    unsigned int           n_inactive_dofs_ = 0;

    bool distributed_stiffness() const;
    bool stiffness_allocated() const;
    void allocate_stiffness();
    template<typename Matrix>
    void regularize_inactive_dofs(Matrix &matrix, const dealii::IndexSet &rows);
  };
} // namespace coshell::driver
