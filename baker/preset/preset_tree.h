// A preset's YAML as the reader sees it: parsed, merged with its bases
// (preset/preset_extends.h) and overridden (preset/preset_overrides.h).
// Internal to the preset stage.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "preset/load_preset.h"
#include "preset/yaml_field.h"

namespace rockbake {

struct PresetTree {
  YAML::Node root;
  Source source;                             // where each key path came from, and the overrides
  std::vector<std::filesystem::path> files;  // the preset, then its bases
};

// Throws InputError for text that is not one YAML map, a broken extends chain or a bad override.
PresetTree readPresetTree(const std::string& yaml_text, const std::filesystem::path& file,
                          const PresetOverrides& overrides);

// The text of a preset file; InputError naming it when it cannot be read.
std::string readPresetFile(const std::filesystem::path& file);

}  // namespace rockbake
