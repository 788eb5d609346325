#pragma once

#include <deal.II/base/parameter_handler.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>

#include <functional>

namespace coshell::base
{
  /// Starts MPI unless it is running already. coshell starts MPI only when
  /// something needs it (a Trilinos solver, or a launch by mpirun):
  /// OpenMPI's start-up alone takes longer than a whole small scene
  /// (doc/performance.md). MPI is finalized at exit.
  void ensure_mpi_initialized();

  /// True when the process was started by mpirun/mpiexec (OpenMPI, MPICH
  /// or PMIx environment variables are set).
  bool launched_by_mpi_launcher();

  /// Ranks of MPI_COMM_WORLD (1 while MPI is not running).
  unsigned int n_ranks();
  /// This process's rank in MPI_COMM_WORLD (0 while MPI is not running).
  unsigned int this_rank();
  /// True when several ranks share the work of one scene.
  bool distributed();
  /// True on the one rank that writes files and the log (rank 0).
  bool writes_output();

  /// Sums 'values' over all ranks in place; every rank gets the same
  /// bits. A no-op on one rank.
  void sum_over_ranks(dealii::Vector<double> &values);
  void sum_over_ranks(dealii::SparseMatrix<double> &matrix);
  /// The largest value of 'flag' over all ranks (a failure on one rank
  /// that the others must hear of before they wait in a collective).
  bool any_rank(bool flag);
  /// The largest 'value' over all ranks.
  int largest_over_ranks(int value);
  /// Runs 'work' on each rank in turn (a file some library opens for
  /// writing, which the others cannot open meanwhile). An exception is
  /// raised on its rank after the last turn, so no rank is left waiting.
  void one_rank_at_a_time(const std::function<void()> &work);
  /// For a rank that stops on an error: waits a few seconds for every other
  /// rank to call this too (a non-blocking barrier on a communicator of its
  /// own). True when they all did (the same error everywhere, e.g. a bad
  /// parameter), so one rank may report for all; false when some did not
  /// (they may wait in a collective for ever). True on one rank.
  bool every_rank_stops();
  /// Ends every rank of a distributed run after an error on some of them
  /// (the others may wait in a collective for ever); returns otherwise.
  void abort_other_ranks(int status);

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

  /// While it lives (and if 'serial'), the BLAS runs on the calling
  /// thread alone; after, on as many threads as before. For work made of
  /// BLAS calls too small to share between threads.
  class SerialBlas
  {
  public:
    explicit SerialBlas(bool serial);
    ~SerialBlas();
    SerialBlas(const SerialBlas &)            = delete;
    SerialBlas &operator=(const SerialBlas &) = delete;

  private:
    /// OpenBLAS's thread count when made (0: not serial, or no OpenBLAS).
    int threads_before_;
  };
} // namespace coshell::base
