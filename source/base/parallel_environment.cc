#include <coshell/base/parallel_environment.h>

#include <deal.II/base/multithread_info.h>

#include <dlfcn.h>
#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <exception>
#include <thread>
#include <vector>

namespace coshell::base
{
  using namespace dealii;

  namespace
  {
    /// A duplicate of MPI_COMM_WORLD for the handshake of failing ranks
    /// alone (every_rank_stops): its barrier can never be matched with a
    /// collective of the code's own that another rank is waiting in.
    MPI_Comm error_communicator = MPI_COMM_NULL;

    void finalize_mpi()
    {
      int finalized = 0;
      MPI_Finalized(&finalized);
      if (finalized)
        return;
      if (error_communicator != MPI_COMM_NULL)
        MPI_Comm_free(&error_communicator);
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
    // Made now, while every rank is here: a duplicate is a collective,
    // which a failing rank could not start alone.
    MPI_Comm_dup(MPI_COMM_WORLD, &error_communicator);
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

  namespace
  {
    /// MPI_Comm_size or MPI_Comm_rank of MPI_COMM_WORLD, or 'without_mpi'
    /// while MPI is not running.
    unsigned int world(int (*query)(MPI_Comm, int *), int without_mpi)
    {
      int initialized = 0;
      MPI_Initialized(&initialized);
      int value = without_mpi;
      if (initialized)
        query(MPI_COMM_WORLD, &value);
      return value;
    }
  } // namespace

  unsigned int n_ranks()
  {
    return world(MPI_Comm_size, 1);
  }

  unsigned int this_rank()
  {
    return world(MPI_Comm_rank, 0);
  }

  bool distributed()
  {
    return n_ranks() > 1;
  }

  bool writes_output()
  {
    return this_rank() == 0;
  }

  namespace
  {
    void sum_in_place(double *values, std::size_t n)
    {
      // MPI counts are int: long arrays go in chunks.
      constexpr std::size_t chunk = std::size_t(1) << 30;
      for (std::size_t start = 0; start < n; start += chunk)
        MPI_Allreduce(MPI_IN_PLACE, values + start,
                      static_cast<int>(std::min(chunk, n - start)), MPI_DOUBLE,
                      MPI_SUM, MPI_COMM_WORLD);
    }
  } // namespace

  void sum_over_ranks(Vector<double> &values)
  {
    if (distributed())
      sum_in_place(values.begin(), values.size());
  }

  void sum_over_ranks(SparseMatrix<double> &matrix)
  {
    if (!distributed())
      return;
    // Every rank holds the same pattern, so the stored entries line up.
    // deal.II keeps them in one array, row after row, and a square pattern
    // stores each row's diagonal first, so row 0's diagonal is its start:
    // summing it in place spares a copy of 8 bytes per entry (0.34 KB per
    // DoF) in the replicated Newton and dynamic assemblies.
    if (matrix.n_nonzero_elements() == 0)
      return;
    AssertThrow(matrix.m() == matrix.n(), ExcNotQuadratic());
    sum_in_place(&matrix.diag_element(0), matrix.n_nonzero_elements());
  }

  bool any_rank(bool flag)
  {
    if (!distributed())
      return flag;
    int local = flag ? 1 : 0, global = 0;
    MPI_Allreduce(&local, &global, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
    return global != 0;
  }

  int largest_over_ranks(int value)
  {
    if (!distributed())
      return value;
    int largest = value;
    MPI_Allreduce(&value, &largest, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
    return largest;
  }

  void one_rank_at_a_time(const std::function<void()> &work)
  {
    std::exception_ptr failure;
    for (unsigned int turn = 0; turn < n_ranks(); ++turn)
    {
      if (turn == this_rank())
        try
        {
          work();
        }
        catch (...)
        {
          failure = std::current_exception();
        }
      if (distributed())
        MPI_Barrier(MPI_COMM_WORLD);
    }
    if (failure)
      std::rethrow_exception(failure);
  }

  namespace
  {
    // How long a failing rank waits for the others to fail as well. The
    // ranks run the same steps on replicated data, so a failure they share
    // (a bad parameter, a solve that did not converge) reaches every rank
    // between the same two collectives, close together in time; the margin
    // is for a loaded or oversubscribed machine. A rank whose failure is
    // its own pays this wait once, before it ends the run.
    constexpr double stop_wait_seconds = 5;
  } // namespace

  bool every_rank_stops()
  {
    if (!distributed())
      return true;
    if (error_communicator == MPI_COMM_NULL) // MPI started by someone else
      return false;
    MPI_Request request;
    MPI_Ibarrier(error_communicator, &request);
    const auto give_up = std::chrono::steady_clock::now() +
                         std::chrono::duration<double>(stop_wait_seconds);
    int arrived = 0;
    while (MPI_Test(&request, &arrived, MPI_STATUS_IGNORE) == MPI_SUCCESS &&
           !arrived && std::chrono::steady_clock::now() < give_up)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    return arrived != 0;
  }

  void abort_other_ranks(int status)
  {
    if (distributed())
      MPI_Abort(MPI_COMM_WORLD, status);
  }

  namespace
  {
    // The BLAS behind SuiteSparse (OpenBLAS on Debian with the project's
    // set-up) and an OpenMP runtime start threads of their own, one per
    // core, and OpenBLAS's spin while idle: with Parallel/Threads = 1 they
    // would still burn the other cores. Both get the scheduler's thread
    // count, through whatever the process has loaded (the reference BLAS
    // has no such call, then nothing happens).
    template<typename Function>
    Function *find_function(const char *name)
    {
      return reinterpret_cast<Function *>(dlsym(RTLD_DEFAULT, name));
    }

    // omp_set_num_threads does not bound a region that names its own
    // thread count: Debian's CHOLMOD (SuiteSparse 5.12) asks for
    // CHOLMOD_OMP_NUM_THREADS = 4 in its supernodal factorization. On one
    // thread those wake-ups and futex waits cost more than the
    // factorization (the kernel's scheduler dominates the profile). On
    // two threads libgomp's team spins against OpenBLAS's and the cells'
    // threads and the factorizations take many times longer, even with
    // the dynamic adjustment that caps a region at the idle cores. The
    // parallel work of a factorization is in the BLAS, so no OpenMP
    // region may be active (max-active-levels 0), whatever the thread
    // count (a large plate solves as fast: doc/performance/scaling.md). It is a
    // setting of the calling thread (GCC 12), the one the solvers run on.
    void limit_openmp_regions()
    {
      if (const auto set_levels =
              find_function<void(int)>("omp_set_max_active_levels"))
        set_levels(0);
    }

    void limit_library_threads(unsigned int threads)
    {
      for (const char *name :
           {"openblas_set_num_threads", "omp_set_num_threads"})
        if (const auto set = find_function<void(int)>(name))
          set(static_cast<int>(threads));
      limit_openmp_regions();
    }
  } // namespace

  namespace
  {
    /// OpenBLAS's thread count (0: no OpenBLAS in the process).
    int blas_threads()
    {
      static const auto get = find_function<int()>("openblas_get_num_threads");
      return get ? get() : 0;
    }

    void set_blas_threads(int threads)
    {
      static const auto set =
          find_function<void(int)>("openblas_set_num_threads");
      if (set)
        set(threads);
    }
  } // namespace

  SerialBlas::SerialBlas(bool serial)
      : threads_before_(serial ? blas_threads() : 0)
  {
    // The count before is put back, not Parallel/Threads': a program
    // that set OpenBLAS itself keeps its setting.
    if (threads_before_ > 1)
      set_blas_threads(1);
  }

  SerialBlas::~SerialBlas()
  {
    if (threads_before_ > 1)
      set_blas_threads(threads_before_);
  }

  void ThreadSettings::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Parallel");
    prm.declare_entry("Threads", "0", Patterns::Integer(0),
                      "Number of threads for assembly, and for the BLAS "
                      "(OpenBLAS) the linear solvers use; "
                      "0 = all cores (capped by the environment variable "
                      "DEAL_II_NUM_THREADS if set). A CHOLMOD factorization "
                      "of under 1e8 flops runs its BLAS on one thread, and "
                      "OpenMP regions (CHOLMOD opens some) run on one "
                      "thread at any setting. Unit: dimensionless (a "
                      "count).");
    prm.leave_subsection();
  }

  void ThreadSettings::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Parallel");
    const unsigned int threads = prm.get_integer("Threads");
    prm.leave_subsection();
    MultithreadInfo::set_thread_limit(
        threads == 0 ? numbers::invalid_unsigned_int : threads);
    limit_library_threads(MultithreadInfo::n_threads());
  }

  unsigned int ThreadSettings::n_threads()
  {
    return MultithreadInfo::n_threads();
  }
} // namespace coshell::base
