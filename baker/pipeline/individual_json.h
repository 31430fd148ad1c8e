// What a seed drew from its preset's family (docs/model.md §12), as asset.json,
// stats.json and `rockbake preset show` record it:
//
//   {"scale", "stretch": [x, y, z], "azimuth_deg", "tilt_deg", "tilt_toward_deg",
//    "bend", "bend_toward_deg", "taper", "twist_deg",
//    "cuts": [{"joint_set", "normal": [x, y, z], "depth"}, ..],
//    "grid_size": [x, y, z], "pivot": [x, y, z], "apron_room"}
//
// Lengths in world units, rounded to 1e-6. Null for a preset without a family.
#pragma once

#include <nlohmann/json.hpp>

#include "preset/preset.h"

namespace rockbake {

nlohmann::ordered_json individualJson(const SimParams& params);

}  // namespace rockbake
