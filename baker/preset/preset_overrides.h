// Command-line overrides on a preset's merged YAML, before it is read
// (docs/command-line.md): --set key.path=VALUE (list items by index), --seed
// and --resolution. Internal to the preset stage.
#pragma once

#include <yaml-cpp/yaml.h>

#include "preset/load_preset.h"
#include "preset/yaml_field.h"

namespace rockbake {

// The smallest a followed map gets, texels: a preview's maps stay legible.
inline constexpr int kMinFollowedMapSize = 256;

// LOD0's map size for a bake at `resolution` of a preset whose own grid.resolution is
// `own_resolution` and whose texture.size is `size` (a power of two): the power of two at
// least size · resolution / own_resolution (the preset's texels per voxel or more), at least
// kMinFollowedMapSize and never above `size`. A finer bake keeps `size`.
int mapSizeAtResolution(int size, int own_resolution, int resolution);

// Applies `overrides` to `root` in order (sets, then seed, then resolution) and
// records in source.overrides what to name as each key path's location. A set
// of one of a set of alternatives replaces the others (schema::siblingsReplacedBy:
// `cycles` replaces `time`). --resolution below the preset's own also sets texture.size by
// mapSizeAtResolution, unless a set names texture.size. Throws InputError at the flag for
// a malformed set (no '=', bad YAML, an empty key part, an index past a list's
// end, a key inside a value that is not a map).
void applyOverrides(YAML::Node& root, const PresetOverrides& overrides, Source& source);

}  // namespace rockbake
