#pragma once

#include <chrono>

namespace coshell::solvers
{
  /// Adds the wall-clock seconds of its scope to a counter (the timings
  /// summary.json reports: linear solver, contact detection, ...).
  class Stopwatch
  {
  public:
    explicit Stopwatch(double &total)
        : total_(total), start_(std::chrono::steady_clock::now())
    {
    }
    Stopwatch(const Stopwatch &)            = delete;
    Stopwatch &operator=(const Stopwatch &) = delete;
    ~Stopwatch()
    {
      total_ += std::chrono::duration<double>(std::chrono::steady_clock::now() -
                                              start_)
                    .count();
    }

  private:
    double                               &total_;
    std::chrono::steady_clock::time_point start_;
  };
} // namespace coshell::solvers
