// The installed catalogue presets (docs/libraries.md, "Sharing presets"): the presets/
// folder rockbake ships, installed as <prefix>/share/rockbake/presets (in a build tree,
// build/share/rockbake/presets, a link to the source tree's presets/). A preset extends
// one by name, `extends: rockbake:base.yaml`, resolved through the data folder
// (platform/data_dir.h), so a preset that uses the house style needs no copy of it.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rockbake {

// What an `extends` value starts with to name an installed catalogue preset.
inline constexpr std::string_view kCataloguePrefix = "rockbake:";

// The catalogue folder: <data folder>/presets. Empty when the data folder is unknown.
std::filesystem::path catalogueDir();

// "rockbake:NAME" → NAME; nothing for any other value.
std::optional<std::string> catalogueName(const std::string& written);

// Why NAME names no catalogue file (empty, absolute, with a `..` or `.` part, a backslash or
// a control byte), or nothing when it is a plain relative name such as `base.yaml`.
std::optional<std::string> catalogueNameProblem(const std::string& name);

// The catalogue's presets and bases: the .yaml files directly in catalogueDir(), sorted.
std::vector<std::string> cataloguePresetNames();

}  // namespace rockbake
