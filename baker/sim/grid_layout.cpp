#include "sim/grid_layout.h"

#include "sim/bubble.h"
#include "sim/distance_field.h"
#include "sim/durability.h"
#include "sim/family.h"
#include "sim/shapes.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace rockbake {

GridLayout computeGridLayout(const SimParams& preset) {
  GridLayout g;
  // The voxel size is the preset's; the domain is fitted to the family's individual (sim/family.h).
  const Vec3d& declared = preset.grid.size;
  g.h = std::max({declared[0], declared[1], declared[2]}) / double(preset.grid.resolution);
  const Vec3d size = simulationDomain(preset);
  int reach = 0;
  for (const auto& band : preset.bubbles) reach = std::max(reach, bubbleReach(band.bubble, g.h));
  // Bubble graphs that keyframes switch to later need the same margin.
  for (const auto& k : preset.durability.keyframes)
    if (k.bubbles)
      for (const auto& band : *k.bubbles) reach = std::max(reach, bubbleReach(band.bubble, g.h));
  g.margin = reach + 1;
  const auto cells = [&](double extent) { return std::max(1, int(std::lround(extent / g.h))); };
  g.nx = cells(size[0]) + 2 * g.margin;
  g.ny = cells(size[1]) + 2 * g.margin;
  g.nz = cells(size[2]) + g.margin;
  g.origin = {-g.margin * g.h, -g.margin * g.h, 0.0};
  g.domain_height = size[2];
  g.ground = preset.grid.ground;
  return g;
}

void requireSimulationCells(const GridLayout& layout) {
  if (layout.cellCount() > kMaxSimulationCells)
    throw std::invalid_argument("a " + std::to_string(layout.nx) + "×" + std::to_string(layout.ny) + "×" +
                                std::to_string(layout.nz) + " grid has more cells than the simulation numbers (" +
                                std::to_string(kMaxSimulationCells) + ")");
}

int largestResolutionWithinCellLimit(const SimParams& params) {
  SimParams trial = params;
  const auto fits = [&](int resolution) {
    trial.grid.resolution = resolution;
    return computeGridLayout(trial).cellCount() <= kMaxSimulationCells;
  };
  // Cells grow with the resolution (the margin, in voxels, too): bisect for the last that fits.
  int lo = GridParams::kMinResolution, hi = params.grid.resolution;
  if (fits(hi)) return hi;
  if (!fits(lo)) return lo;
  while (hi - lo > 1) {
    const int mid = lo + (hi - lo) / 2;
    (fits(mid) ? lo : hi) = mid;
  }
  return lo;
}

std::uint64_t estimateSimulationBytes(const GridLayout& layout) {
  const std::uint64_t cells = layout.cellCount();
  const std::uint64_t rows = std::uint64_t(layout.ny) * std::uint64_t(layout.nz);
  // Rock lies inside the domain: the grid less its margin on four sides and the top.
  const auto inner = [&](int n, int sides) { return std::uint64_t(std::max(0, n - sides * layout.margin)); };
  const std::uint64_t domain = inner(layout.nx, 2) * inner(layout.ny, 2) * inner(layout.nz, 1);
  const std::uint64_t apron = std::uint64_t(layout.margin);
  const std::uint64_t field_bits = (layout.nx + 2 * apron + 128) * (layout.ny + 2 * apron) * (layout.nz + 2 * apron);
  // Colluvium's solid cells, a bit a cell in columns of whole 64-bit words.
  const std::uint64_t column_bytes =
      std::uint64_t(layout.nx) * std::uint64_t(layout.ny) * std::uint64_t((layout.nz + 63) / 64) * 8;
  // material (1 byte a cell); integrity and durability (4 + 4 bytes a rock
  // cell, at most the domain, plus a span header per row for each); the air
  // field; five bit planes (exposed, colluvium, and rockfall's visited,
  // removed and clustered marks) and colluvium's columns; work lists for the
  // exposed voxels, at most about a tenth of the domain at once (cell, flag
  // and counts: 16 bytes).
  return cells + domain * 8 + rows * 2 * 32 + field_bits / 8 + cells * 5 / 8 + column_bytes + domain / 10 * 16;
}

std::uint64_t estimateSimulationBytes(const SimParams& params) {
  const GridLayout layout = computeGridLayout(params);
  // The start's distance field, as far out as variation or the rind reads it.
  double reach = 0.0;
  if (params.shape.variation && params.shape.variation->amplitude > 0)
    reach = variationReach(*params.shape.variation, layout.h);
  if (params.durability.rind) reach = std::max(reach, rindReach(params.durability.rind->depth, layout.h));
  const std::uint64_t distance_field = reach > 0 ? signedDistanceBytes(layout, reach) : 0;
  return estimateSimulationBytes(layout) + distance_field;
}

}  // namespace rockbake
