#include <coshell/base/parallel_environment.h>
#include <coshell/driver/interruption.h>

#include <csignal>

namespace coshell::driver
{
  namespace
  {
    volatile std::sig_atomic_t received_signal = 0;

    extern "C" void remember_signal(int signal)
    {
      received_signal = signal;
    }
  } // namespace

  void install_interrupt_handlers()
  {
    std::signal(SIGINT, remember_signal);
    std::signal(SIGTERM, remember_signal);
  }

  int interrupt_signal()
  {
    // mpirun forwards the signal to every rank, but not at the same
    // instant: the ranks agree, so that all stop at the same step.
    return base::largest_over_ranks(received_signal);
  }
} // namespace coshell::driver
