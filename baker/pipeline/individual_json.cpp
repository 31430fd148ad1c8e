#include "pipeline/individual_json.h"

#include <cmath>

#include "sim/family.h"

namespace rockbake {
namespace {

double rounded(double v) {
  const double r = std::round(v * 1e6) / 1e6;
  return r == 0.0 ? 0.0 : r;  // no "-0.0"
}
nlohmann::ordered_json rounded(const Vec3d& v) {
  return {rounded(v[0]), rounded(v[1]), rounded(v[2])};
}

}  // namespace

nlohmann::ordered_json individualJson(const SimParams& params) {
  if (!params.family) return nullptr;
  const Individual ind = drawIndividual(params);
  nlohmann::ordered_json cuts = nlohmann::ordered_json::array();
  for (const Individual::Cut& c : ind.cuts)
    cuts.push_back({{"joint_set", c.joint_set}, {"normal", rounded(c.normal)}, {"depth", rounded(c.depth)}});
  return {{"scale", rounded(ind.scale)},
          {"stretch", rounded(ind.stretch)},
          {"azimuth_deg", rounded(ind.azimuth)},
          {"tilt_deg", rounded(ind.tilt)},
          {"tilt_toward_deg", rounded(ind.tilt_toward)},
          {"bend", rounded(ind.bend)},
          {"bend_toward_deg", rounded(ind.bend_toward)},
          {"taper", rounded(ind.taper)},
          {"twist_deg", rounded(ind.twist)},
          {"cuts", cuts},
          {"grid_size", rounded(ind.domain)},
          {"pivot", rounded(ind.pivot)},
          {"apron_room", rounded(ind.apron)}};
}

}  // namespace rockbake
