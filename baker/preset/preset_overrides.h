// Command-line overrides on a preset's merged YAML, before it is read
// (docs/command-line.md): --set key.path=VALUE (list items by index), --seed
// and --resolution. Internal to the preset stage.
#pragma once

#include <yaml-cpp/yaml.h>

#include "preset/load_preset.h"
#include "preset/yaml_field.h"

namespace rockbake {

// Applies `overrides` to `root` in order (sets, then seed, then resolution) and
// records in source.overrides what to name as each key path's location. A set
// of one of a set of alternatives replaces the others (schema::siblingsReplacedBy:
// `cycles` replaces `time`). Throws InputError at the flag for
// a malformed set (no '=', bad YAML, an empty key part, an index past a list's
// end, a key inside a value that is not a map).
void applyOverrides(YAML::Node& root, const PresetOverrides& overrides, Source& source);

}  // namespace rockbake
