#pragma once
//! \file stopwatch.h
//! \brief Wall-clock time of a step, for the `seconds` fields of the results.

#include <chrono>

namespace polycube::core {

//! Measures the wall time since its construction or its last restart().
class Stopwatch {
 public:
  Stopwatch() : start_(Clock::now()) {}
  //! Seconds since the construction or the last restart().
  [[nodiscard]] double seconds() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }
  void restart() { start_ = Clock::now(); }

 private:
  using Clock = std::chrono::steady_clock;
  Clock::time_point start_;
};

}  // namespace polycube::core
