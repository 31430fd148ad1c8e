// Wall-clock timing for stage profiles (stats.json "stages"). Not part of any
// result: timings never decide an output.
#pragma once

#include <chrono>

namespace rockbake {

class Stopwatch {
 public:
  using Clock = std::chrono::steady_clock;

  // Seconds since construction.
  double elapsed() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }
  // Seconds since the last lap (or construction).
  double lap() {
    const auto now = Clock::now();
    const double seconds = std::chrono::duration<double>(now - last_).count();
    last_ = now;
    return seconds;
  }

 private:
  Clock::time_point start_ = Clock::now();
  Clock::time_point last_ = start_;
};

}  // namespace rockbake
