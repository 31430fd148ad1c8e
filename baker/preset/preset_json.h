// The resolved preset as JSON: every key, defaults filled in (stats.json "preset").
#pragma once

#include <string>

#include <nlohmann/json_fwd.hpp>

#include "preset/preset.h"

namespace rockbake {

nlohmann::json presetToJson(const Preset& preset);

// A stable fingerprint of the resolved preset: 16 hex digits of FNV-1a 64 over
// presetToJson(preset).dump(). Equal presets (after defaults) hash equal.
std::string presetHash(const Preset& preset);
// The same fingerprint of a resolved preset already in JSON (stats.json "preset").
std::string presetHash(const nlohmann::json& resolved);

}  // namespace rockbake
