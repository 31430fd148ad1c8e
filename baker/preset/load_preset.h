// Reading presets: YAML → validated Preset (SPEC §5, §6).
//
// Every problem throws InputError naming the file, line, column (1-based) and
// key path ("bubbles.0.bubble.sphere.radius"), what is wrong and what to do.
// Unknown keys are rejected with a "did you mean" suggestion. Relative paths in
// the preset (shape.image.path) are resolved against the preset's folder and
// must exist. A grid too large for this machine's memory is refused here,
// before anything is allocated.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "preset/preset.h"

namespace rockbake {

// Command-line overrides, applied after reading the file and before validation.
struct PresetOverrides {
  std::vector<std::string> sets;      // "key.path=YAML value", list items by index
  std::optional<std::uint64_t> seed;  // --seed
  std::optional<int> resolution;      // --resolution
};

Preset loadPreset(const std::filesystem::path& file, const PresetOverrides& overrides = {});

// Same, from text in memory; `file` names it in messages and anchors relative paths.
Preset parsePreset(const std::string& yaml_text, const std::filesystem::path& file,
                   const PresetOverrides& overrides = {});

}  // namespace rockbake
