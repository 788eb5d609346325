#pragma once

#include <stdexcept>
#include <string>

namespace coshell::driver
{
  /// SIGINT and SIGTERM set a flag instead of killing the process, so the
  /// scene can finish its step, write a checkpoint and stop. Installed by
  /// the coshell executable, never by the library on its own.
  void install_interrupt_handlers();
  /// The signal received (0 if none).
  int interrupt_signal();

  /// Thrown when a run stops on a signal; coshell exits with status 3.
  class Interrupted : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };
} // namespace coshell::driver
