// How much memory this process may use: what the memory guards compare their
// estimates with (pipeline/read_inputs.h before a bake, the studio before work
// that cannot recover from running out part-way, docs/studio.md "Memory").
// A limit on the process (ulimit -v, a batch system's) counts as the machine's
// memory. Linux only (/proc).
#pragma once

#include <cstdint>

namespace rockbake {

// The machine's physical memory, or the process's address-space limit when that is lower.
std::uint64_t memoryLimitBytes();

// How much more this process may take now: the smaller of what its address-space
// limit leaves above its current size, and the memory the machine has available.
std::uint64_t memoryHeadroomBytes();

}  // namespace rockbake
