#include "pipeline/bake_phases.h"

#include <stdexcept>
#include <string>

namespace rockbake {

const BakePhase& bakePhase(std::string_view name) {
  for (const BakePhase& p : kBakePhases)
    if (p.name == name) return p;
  throw std::logic_error("no bake phase is called " + std::string(name) + " (pipeline/bake_phases.h)");
}

double bakeProgress(std::string_view phase, double done, double of) {
  const BakePhase& p = bakePhase(phase);
  return p.start + p.share * done / of;
}

nlohmann::ordered_json bakeTimingsJson(const PhaseTimes& times) {
  for (const PhaseTime& t : times.all()) bakePhase(t.name);
  nlohmann::ordered_json stages = nlohmann::ordered_json::object();
  for (const BakePhase& p : kBakePhases)
    if (const auto seconds = times.seconds(p.name)) stages[std::string(p.name)] = *seconds;
  return stages;
}

}  // namespace rockbake
