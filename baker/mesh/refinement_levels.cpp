#include "mesh/refinement_levels.h"

namespace rockbake {

namespace {
constexpr double kVerticesPerPeriod = 4.0;  // refined edges no longer than period / 4
}  // namespace

int refinementLevels(int max_levels, double voxel, const std::optional<NoiseParams>& detail) {
  if (!detail || detail->amplitude <= 0.0) return max_levels;
  const double wanted = detail->period / kVerticesPerPeriod;
  int levels = 0;
  for (double edge = voxel; levels < max_levels && edge > wanted; edge *= 0.5) ++levels;
  return levels;
}

}  // namespace rockbake
