#pragma once

#include <chrono>

namespace coshell::base
{
  /// Wall-clock seconds from 'start' to now.
  inline double
  seconds_since(const std::chrono::steady_clock::time_point &start)
  {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() -
                                         start)
        .count();
  }

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
} // namespace coshell::base
