#include <coshell/solvers/parallel_environment.h>

#include <deal.II/base/multithread_info.h>

#include <mpi.h>

#include <cstdlib>

namespace coshell::solvers
{
  using namespace dealii;

  namespace
  {
    void finalize_mpi()
    {
      int finalized = 0;
      MPI_Finalized(&finalized);
      if (!finalized)
        MPI_Finalize();
    }
  } // namespace

  void ensure_mpi_initialized()
  {
    int initialized = 0;
    MPI_Initialized(&initialized);
    if (initialized)
      return;
    // Assembly threads never call MPI, so "funneled" suffices. Objects that
    // hold MPI handles are created after this point, hence destroyed
    // before the exit handler runs.
    int provided = 0;
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
    std::atexit(finalize_mpi);
  }

  bool launched_by_mpi_launcher()
  {
    for (const char *variable :
         {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK", "MPI_LOCALNRANKS"})
      if (std::getenv(variable))
        return true;
    return false;
  }

  void ThreadSettings::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Parallel");
    prm.declare_entry("Threads", "0", Patterns::Integer(0),
                      "Number of threads for assembly (dimensionless); 0 = "
                      "all cores (capped by the environment variable "
                      "DEAL_II_NUM_THREADS if set).");
    prm.leave_subsection();
  }

  void ThreadSettings::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Parallel");
    const unsigned int threads = prm.get_integer("Threads");
    prm.leave_subsection();
    MultithreadInfo::set_thread_limit(
        threads == 0 ? numbers::invalid_unsigned_int : threads);
  }

  unsigned int ThreadSettings::n_threads()
  {
    return MultithreadInfo::n_threads();
  }
} // namespace coshell::solvers
