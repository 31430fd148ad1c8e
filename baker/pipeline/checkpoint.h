// Checkpoint files (docs/libraries.md): `bake --checkpoint-every T` writes
// OUT/<name>/checkpoints/<time>.rbk, and `rockbake resume` continues one
// (pipeline/resume_plan.h). The format, bytes to a Checkpoint and back, is the
// simulation's (sim/checkpoint_format.h); this is its file I/O.
#pragma once

#include <filesystem>

#include "sim/checkpoint_format.h"

namespace rockbake {

// Atomic: a checkpoint being written is never mistaken for a whole one.
void writeCheckpoint(const std::filesystem::path& file, const Checkpoint& checkpoint);

// The checkpoint in `file`. Throws InputError naming `file` when it is not a
// regular file (a FIFO or a device is refused at once, without reading), cannot
// be read, or is refused by parseCheckpoint. The header is checked before the
// rest is read, and a file larger than a checkpoint of its header's grid is
// refused unread: a foreign or sparse file of gigabytes costs a few bytes.
Checkpoint readCheckpoint(const std::filesystem::path& file);

}  // namespace rockbake
