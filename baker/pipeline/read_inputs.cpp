#include "pipeline/read_inputs.h"

#include <unistd.h>

#include <cstdint>

#include <fmt/format.h>

#include "core/error.h"
#include "sim/grid_layout.h"

namespace rockbake {

void checkGridFitsInMemory(const Preset& preset) {
  const GridLayout layout = computeGridLayout(preset);
  const std::uint64_t needed = estimateSimulationBytes(layout);
  const std::uint64_t physical = std::uint64_t(::sysconf(_SC_PHYS_PAGES)) * std::uint64_t(::sysconf(_SC_PAGESIZE));
  if (needed > physical / 10 * 6)
    throw InputError(preset.locate("grid.resolution"), "grid.resolution",
                     fmt::format("a {}×{}×{} grid needs about {} MiB; this machine has {} MiB", layout.nx, layout.ny,
                                 layout.nz, needed >> 20, physical >> 20),
                     "lower grid.resolution (or --resolution)");
}

ResolvedShape readInputs(const Preset& preset) {
  checkGridFitsInMemory(preset);
  return resolveShape(preset);
}

}  // namespace rockbake
