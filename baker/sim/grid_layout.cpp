#include "sim/grid_layout.h"

#include "sim/bubble.h"

#include <algorithm>
#include <cmath>

namespace rockbake {

GridLayout computeGridLayout(const SimParams& preset) {
  GridLayout g;
  const Vec3d& size = preset.grid.size;
  g.h = std::max({size[0], size[1], size[2]}) / double(preset.grid.resolution);
  int reach = 0;
  for (const auto& band : preset.bubbles) reach = std::max(reach, bubbleReach(band.bubble, g.h));
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

std::uint64_t estimateSimulationBytes(const GridLayout& layout) {
  // material (1) + integrity (4) + durability (4) + an exposure flag (1)
  // + the air bit field with its apron + work lists for about a third of the
  // cells being exposed at once (index + integrity + flag).
  const std::uint64_t cells = layout.cellCount();
  const std::uint64_t apron = std::uint64_t(layout.margin);
  const std::uint64_t field_bits = (layout.nx + 2 * apron + 128) * (layout.ny + 2 * apron) * (layout.nz + 2 * apron);
  return cells * 10 + field_bits / 8 + cells / 3 * 9;
}

}  // namespace rockbake
