// `extends: base.yaml` (docs/preset-reference.md): a preset's YAML merged over
// its chain of base presets, before overrides and reading. Internal to the
// preset stage.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "preset/yaml_field.h"

namespace rockbake {

// Replaces `root`'s `extends` by the merged base chain: maps deep-merged with
// the preset's keys winning, lists and scalars replaced whole, and a choice
// among alternatives (schema::mergeRules(): `cycles` for `time`, `sphere` for
// `box`) dropping the base's. `file` is absolute; `name` names it in messages;
// `chain` collects the files read, this one first; `origins` receives which
// file wrote each key path. Throws InputError at the `extends` for a base that
// is missing, unreadable, not a map or part of a cycle.
void resolveExtends(YAML::Node root, const std::string& name, const std::filesystem::path& file,
                    std::vector<std::filesystem::path>& chain, std::vector<Origin>& origins);

}  // namespace rockbake
