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

// From here on, blocks of a mebibyte or more (a texture map's bands, the texel map, the
// simulation's arrays) are mapped afresh and unmapped when freed. By default the C library
// raises that threshold to the largest block freed so far, up to 32 MiB, and keeps such
// blocks in its heaps once freed (16 to 74 MiB of a hero's texture set's peak). The
// command line sets it first thing, so every stage and every bake of a library runs alike
// (docs/textures.md §11). A no-op outside glibc.
void returnLargeBlocksToTheSystem();

}  // namespace rockbake
