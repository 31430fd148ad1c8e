// The resolved preset as JSON: every key, defaults filled in (stats.json "preset"),
// written by the schema's table (preset/schema.h), so it reads back as the same preset.
#pragma once

#include <nlohmann/json_fwd.hpp>

#include "preset/preset.h"

namespace rockbake {

nlohmann::json presetToJson(const Preset& preset);

}  // namespace rockbake
