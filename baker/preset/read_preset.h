// Reading a preset's merged, overridden YAML into a Preset by the schema's table
// (preset/schema.cpp, docs/preset-reference.md). Internal to the preset stage.
#pragma once

#include <filesystem>

#include <yaml-cpp/yaml.h>

#include "preset/preset.h"
#include "preset/yaml_field.h"

namespace rockbake {

// Reads every key of the table. Each top-level key is read on its own: its
// first problem goes to source.problems (which must be set) and reading goes
// on, so one run finds every top-level key's problem; unknown keys are listed
// first, in reading order, then the others in reading order. Records key
// locations when source.locations is set.
Preset readPreset(const YAML::Node& root, Source& source, const std::filesystem::path& file);

}  // namespace rockbake
