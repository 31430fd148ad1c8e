#include "pipeline/read_inputs.h"

#include <cstdint>

#include <fmt/format.h>

#include "core/error.h"
#include "platform/memory.h"
#include "sim/grid_layout.h"

namespace rockbake {

void checkGridCellCount(const Preset& preset) {
  const GridLayout layout = computeGridLayout(preset);
  if (layout.cellCount() <= kMaxSimulationCells) return;
  throw InputError(
      preset.locate("grid.resolution"), "grid.resolution",
      fmt::format("a {}×{}×{} grid (its air margin included) is {} cells; the simulation numbers at "
                  "most {} (2^32 - 1)",
                  layout.nx, layout.ny, layout.nz, layout.cellCount(), kMaxSimulationCells),
      fmt::format("lower grid.resolution (or --resolution) to {} or less", largestResolutionWithinCellLimit(preset)));
}

void checkGridFitsInMemory(const Preset& preset) {
  const GridLayout layout = computeGridLayout(preset);
  const std::uint64_t needed = estimateSimulationBytes(preset);
  const std::uint64_t physical = memoryLimitBytes();  // a limit on this process (ulimit -v) counts as the machine's
  if (needed > physical / 10 * 6)
    throw InputError(preset.locate("grid.resolution"), "grid.resolution",
                     fmt::format("a {}×{}×{} grid needs about {} MiB; this machine (or process) has {} MiB", layout.nx,
                                 layout.ny, layout.nz, needed >> 20, physical >> 20),
                     "lower grid.resolution (or --resolution)");
}

std::string outOfMemoryMessage(const Preset& preset) {
  return fmt::format("out of memory: lower grid.resolution ({} needs about {} MiB for the simulation alone)",
                     preset.grid.resolution, estimateSimulationBytes(preset) >> 20);
}

ResolvedShape readInputs(const Preset& preset) {
  checkGridCellCount(preset);
  checkGridFitsInMemory(preset);
  return resolveShape(preset);
}

}  // namespace rockbake
