#include <coshell/base/parallel_environment.h>

#include <deal.II/base/parameter_handler.h>

#include <dlfcn.h>
#include <gtest/gtest.h>
#include <omp.h>

#include <string>

namespace
{
  void set_threads(const std::string &threads)
  {
    dealii::ParameterHandler prm;
    coshell::base::ThreadSettings::declare_parameters(prm);
    prm.enter_subsection("Parallel");
    prm.set("Threads", threads);
    prm.leave_subsection();
    coshell::base::ThreadSettings().parse_parameters(prm);
  }

  /// The team size of a region that names its own thread count, as
  /// CHOLMOD's supernodal factorization does (num_threads(4)), which
  /// omp_set_num_threads alone does not bound.
  int team_of_region_asking_for_four()
  {
    int team = 0;
#pragma omp parallel num_threads(4)
    {
#pragma omp single
      team = omp_get_num_threads();
    }
    return team;
  }
} // namespace

TEST(ThreadSettings, NoRegionThatAsksForMoreThreadsIsActiveAtAnyThreadCount)
{
  set_threads("1");
  EXPECT_EQ(team_of_region_asking_for_four(), 1);
  EXPECT_EQ(omp_get_max_threads(), 1);
  // Several threads: the BLAS gets them, OpenMP regions still run on the
  // calling thread alone (CHOLMOD's team of four spun against them).
  set_threads("0");
  EXPECT_EQ(omp_get_max_active_levels(), 0);
  EXPECT_EQ(team_of_region_asking_for_four(), 1);
  EXPECT_EQ(omp_get_max_threads(),
            static_cast<int>(coshell::base::ThreadSettings::n_threads()));
}

// The BLAS on one thread while a SerialBlas lives, on the
// scheduler's count before and after (OpenBLAS, found as coshell finds it; the
// test says nothing where the process has another BLAS).
TEST(ThreadSettings, SerialBlasRunsTheBlasOnOneThreadWhileItLives)
{
  const auto blas_threads = reinterpret_cast<int (*)()>(
      dlsym(RTLD_DEFAULT, "openblas_get_num_threads"));
  if (!blas_threads)
    GTEST_SKIP() << "no OpenBLAS in this process";
  set_threads("2");
  if (coshell::base::ThreadSettings::n_threads() < 2)
  {
    set_threads("0");
    GTEST_SKIP() << "one core: nothing to share";
  }
  EXPECT_EQ(blas_threads(), 2);
  {
    const coshell::base::SerialBlas serial(true);
    EXPECT_EQ(blas_threads(), 1);
  }
  EXPECT_EQ(blas_threads(), 2);
  {
    const coshell::base::SerialBlas shared(false);
    EXPECT_EQ(blas_threads(), 2);
  }
  set_threads("0");
}
