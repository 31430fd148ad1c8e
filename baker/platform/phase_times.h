// Seconds spent per named phase: the one shape every stage gives its timings in (the
// simulation's per cycle, the mesh stage's, the texture set's), and stats.json's "stages"
// is written from (pipeline/bake_phases.h). Wall clock, with the process's CPU seconds
// where a stage measures them. Not part of any result: timings never decide an output.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rockbake {

struct PhaseTime {
  std::string name;
  double seconds = 0.0;
  double cpu_seconds = 0.0;  // all threads; 0 where not measured
};

class PhaseTimes {
 public:
  // Adds to `name`'s entry, appending one in first-recorded order.
  void add(std::string_view name, double seconds, double cpu_seconds = 0.0) {
    for (PhaseTime& t : times_)
      if (t.name == name) {
        t.seconds += seconds, t.cpu_seconds += cpu_seconds;
        return;
      }
    times_.push_back({std::string(name), seconds, cpu_seconds});
  }
  // Every entry of `other`, its name after `prefix`.
  void add(const PhaseTimes& other, std::string_view prefix = "") {
    for (const PhaseTime& t : other.times_) add(std::string(prefix) + t.name, t.seconds, t.cpu_seconds);
  }
  std::optional<double> seconds(std::string_view name) const {
    for (const PhaseTime& t : times_)
      if (t.name == name) return t.seconds;
    return std::nullopt;
  }
  const std::vector<PhaseTime>& all() const { return times_; }

 private:
  std::vector<PhaseTime> times_;
};

}  // namespace rockbake
