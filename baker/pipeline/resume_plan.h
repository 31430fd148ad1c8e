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
// must still hash the same. `sets` may change the keys the schema marks as
// keyframed (schema::keyframedKeys: durability.points, durability.noise,
// bubbles, response) — each named part becomes part of a keyframe at the
// checkpoint's time by applyKeyframeEdit (preset/keyframe_edit.h), as a studio
// edit does: a keyframe already at that time takes the edit, and the preset's
// keyframes after it are dropped (logged), since the resumed run is a new
// branch from the checkpoint — so the result is a preset that reproduces the
// run — and the keys it marks as resumable (rockfall, colluvium, time, cycles,
// until), which apply from the checkpoint on. Anything else (grid, shape, seed,
// resolution, ...) is refused, and so is a keyframed edit at time 0.
// InputError (exit 2) for a refused or invalid edit, or a changed preset.
struct ResumePlan {
  Preset preset;
  PresetOverrides overrides;  // what gives `preset` from the preset file: the checkpoint's, the edits, the keyframes
};
ResumePlan planResume(const Checkpoint& checkpoint, const std::vector<std::string>& sets);

}  // namespace rockbake
