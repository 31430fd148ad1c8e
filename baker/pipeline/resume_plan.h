// `rockbake resume CHECKPOINT --set ...` (docs/libraries.md): the preset a resumed bake
// runs, from a checkpoint read by pipeline/checkpoint.h.
#pragma once

#include <string>
#include <vector>

#include "pipeline/checkpoint.h"
#include "preset/load_preset.h"
#include "preset/preset.h"

namespace rockbake {

// The checkpoint's preset is read again (its text, its bases from disk) and
// must still hash the same. `sets` may change durability.points,
// durability.noise, bubbles and response — each becomes part of a keyframe at
// the checkpoint's time, so the result is a preset that reproduces the run —
// and colluvium, rockfall, time, cycles and until, which apply from the
// checkpoint on. Anything else (grid, shape, seed, resolution, ...) is refused.
// InputError (exit 2) for a refused or invalid edit, or a changed preset.
struct ResumePlan {
  Preset preset;
  PresetOverrides overrides;  // what gives `preset` from the preset file: the checkpoint's, the edits, the keyframes
};
ResumePlan planResume(const Checkpoint& checkpoint, const std::vector<std::string>& sets);

}  // namespace rockbake
