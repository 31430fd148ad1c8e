// Reading presets: YAML → validated Preset (docs/libraries.md, docs/preset-reference.md).
//
// `extends: base.yaml` (relative to the file that says it) merges a base
// preset under this one: maps are deep-merged with this file's keys winning,
// lists and scalars are replaced whole (a kind chosen among alternatives, such
// as `cycles` for `time` or `sphere` for `box`, replaces the base's choice),
// and a base may extend another (a cycle is an error naming the chain).
// Overrides apply to the merged result, and only that is validated, so a base
// may be partial.
//
// Every problem throws InputError naming the file, line, column (1-based) and
// key path ("bubbles.0.bubble.sphere.radius"), what is wrong and what to do; a
// problem in a value a base preset gave is located in that base. The schema's
// table (preset/schema.h) says every key; reads record the keys they ask for
// (preset/yaml_field.h), and any other key is rejected as unknown with a "did
// you mean" suggestion; when there are several problems, unknown keys are
// reported first. Relative paths (shape.image.path,
// shape.mesh.path) are resolved against the folder of the file that gives them
// and must exist; reading them is the inputs stage's (inputs/resolve_shape.h).
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/error.h"
#include "preset/preset.h"

namespace rockbake {

// Command-line overrides, applied after reading the file and before validation.
struct PresetOverrides {
  std::vector<std::string> sets;      // "key.path=YAML value", list items by index, applied in order
  std::optional<std::uint64_t> seed;  // --seed
  std::optional<int> resolution;      // --resolution
  // Optional, parallel to `sets`: what messages name as the location of sets[i]
  // (say "lib.yaml:12:9 (wedge 'tall')"). Missing or empty: "--set <argument>".
  // Last, with a default, so {sets, seed, resolution} still initialises the rest.
  std::vector<std::string> set_origins = {};
};

Preset loadPreset(const std::filesystem::path& file, const PresetOverrides& overrides = {});

// Same, from text in memory; `file` names it in messages and anchors relative paths.
Preset parsePreset(const std::string& yaml_text, const std::filesystem::path& file,
                   const PresetOverrides& overrides = {});

// Every problem of a preset at once, for `rockbake lint`: each part of the
// schema (grid, shape, bubbles, ...) is checked even when an earlier one
// failed, and every unknown key is listed. Problems that stop reading (a
// missing file, malformed YAML, a broken extends chain, a bad --set) come
// alone. Sorted by file (the preset, then its bases), line and column; empty
// when the preset is valid, that is when loadPreset would not throw.
std::vector<InputError> lintPreset(const std::filesystem::path& file, const PresetOverrides& overrides = {});

// What a YAML file beside the presets is, for `rockbake lint`: a preset; a
// base (a map with none of `name`, `shape`, `time`, `cycles`: a house style
// that presets extend, not baked by itself); or a library (a list of presets ×
// seeds × wedges, preset/library.h). Preset when the file cannot be read as
// YAML, so that linting it says why.
enum class PresetFileKind { Preset, Base, Library };
PresetFileKind presetFileKind(const std::filesystem::path& file);

// A base's problems: the base merged under a minimal preset that extends it
// (a name, a box and a time of its own), so that every key the base gives is
// checked and located in the base.
std::vector<InputError> lintBase(const std::filesystem::path& file, const PresetOverrides& overrides = {});

}  // namespace rockbake
