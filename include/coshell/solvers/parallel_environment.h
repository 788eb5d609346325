#pragma once

#include <deal.II/base/parameter_handler.h>

namespace coshell::solvers
{
  /// Starts MPI unless it is running already. coshell starts MPI only when
  /// something needs it (a Trilinos solver, or a launch by mpirun):
  /// OpenMPI's start-up alone takes about 0.4 s, more than a whole
  /// small scene. MPI is finalized at exit.
  void ensure_mpi_initialized();

  /// True when the process was started by mpirun/mpiexec (OpenMPI, MPICH
  /// or PMIx environment variables are set).
  bool launched_by_mpi_launcher();

  /// Shared-memory parallelism, prm subsection "Parallel".
  class ThreadSettings
  {
  public:
    static void declare_parameters(dealii::ParameterHandler &prm);
    /// Reads "Threads" and applies it to deal.II's task scheduler (used by
    /// the WorkStream assembly).
    void parse_parameters(dealii::ParameterHandler &prm);

    /// Threads deal.II's task scheduler uses.
    static unsigned int n_threads();
  };
} // namespace coshell::solvers
