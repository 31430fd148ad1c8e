// Every file a preset reaches (docs/libraries.md, "Sharing presets"): the preset, the
// bases it extends, and every file a path key of the schema names (shape.image.path,
// shape.mesh.path, and any later key whose value is a path: the list comes from the
// schema's table, preset/schema.cpp, not from here), each with the place that names it.
// What `rockbake preset pack` copies and `rockbake lint` checks a pack against.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "core/error.h"

namespace rockbake {

// One place where a file of the preset names another file.
struct PresetFileRef {
  std::filesystem::path from;     // the file that names it: absolute, lexically normal
  SourceLocation where;           // the value's file (as messages name it), line and column
  std::size_t offset = 0;         // the value's byte offset in `from`'s text
  std::string key_path;           // "extends", "shape.image.path"
  std::string written;            // the value as written
  std::filesystem::path target;   // what it names: absolute, lexically normal
  bool catalogue = false;         // `extends: rockbake:NAME` (preset/catalogue.h)
};

struct PresetFiles {
  std::vector<std::filesystem::path> chain;  // the preset, then its bases, absolute and lexically normal
  std::vector<PresetFileRef> refs;           // each base's `extends` in chain order, then the path keys
};

// The keys of the schema whose value is a path, as key path patterns ("shape.image.path"; a list's
// items as "[]"), `extends` left out (it is the chain's).
std::vector<std::string> pathKeyPatterns();

// What the preset reaches, as a bake reads it (no overrides): its chain of bases, and the path keys
// that hold in the merged preset (a path a base gives that the preset replaces is not reached).
// Throws InputError as reading the preset does (a missing base, a broken chain, bad YAML).
PresetFiles presetFiles(const std::filesystem::path& preset);

}  // namespace rockbake
