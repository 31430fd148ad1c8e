// Preset loading: parse (yaml-cpp) → merge `extends` → apply overrides → read
// by the schema's table into plain data. Every read goes through a Field that
// knows its key path and source position, so every error can say where it is.
#include "preset/load_preset.h"

#include <map>
#include <optional>

#include "core/error.h"
#include "preset/preset_extends.h"
#include "preset/preset_overrides.h"
#include "preset/preset_tree.h"
#include "preset/read_preset.h"
#include "preset/yaml_text.h"

namespace rockbake {

PresetTree readPresetTree(const std::string& yaml_text, const std::filesystem::path& file,
                          const PresetOverrides& overrides) {
  PresetTree tree;
  const std::string name = file.string();
  tree.root = loadYamlDocument(yaml_text, name, "a preset");
  if (tree.root.IsSequence())
    throw InputError({name, 1, 1}, "", "this is a library file (a list of presets × seeds × wedges), not a preset",
                     "bake it with `rockbake library " + name + "`; `rockbake lint` checks it as a library");
  if (!tree.root.IsMap()) throw InputError({name, 1, 1}, "", "a preset must be a YAML map (key: value, ...)");
  resolveExtends(tree.root, name, std::filesystem::absolute(file).lexically_normal(), tree.files, tree.source.origins);
  applyOverrides(tree.root, overrides, tree.source);
  return tree;
}

std::string readPresetFile(const std::filesystem::path& file) {
  const std::optional<std::string> text = readYamlFile(file.string(), "a preset");
  if (!text) throw InputError({file.string()}, "", "cannot read the preset file", "check the path");
  return *text;
}

Preset parsePreset(const std::string& yaml_text, const std::filesystem::path& file, const PresetOverrides& overrides) {
  PresetTree tree = readPresetTree(yaml_text, file, overrides);
  std::map<std::string, SourceLocation> locations;
  std::vector<InputError> problems;
  tree.source.locations = &locations;
  tree.source.problems = &problems;
  Preset preset = readPreset(tree.root, tree.source, std::filesystem::absolute(file));
  if (!problems.empty()) throw problems.front();
  preset.sources = std::move(tree.files);
  preset.locations = std::move(locations);
  return preset;
}

Preset loadPreset(const std::filesystem::path& file, const PresetOverrides& overrides) {
  return parsePreset(readPresetFile(file), file, overrides);
}

PresetFileKind presetFileKind(const std::filesystem::path& file) {
  try {
    const YAML::Node root = loadYamlDocument(readPresetFile(file), file.string(), "a preset");
    if (root.IsSequence()) return PresetFileKind::Library;
    if (!root.IsMap()) return PresetFileKind::Preset;
    for (const char* own : {"name", "shape", "time", "cycles"})
      if (root[own].IsDefined()) return PresetFileKind::Preset;
    return PresetFileKind::Base;
  } catch (const InputError&) {
    return PresetFileKind::Preset;  // unreadable: linting it as a preset says why
  }
}

}  // namespace rockbake
