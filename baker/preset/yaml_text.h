// Small wording helpers shared by the YAML readers (presets, library files),
// so their messages read alike.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace YAML {
class Node;
}

namespace rockbake {

// What a node holds, for "expected …, found …": "a map", "a list",
// "nothing (null)", "'text'" or "nothing".
std::string describe(const YAML::Node& node);

// A scalar that is a whole number >= 0 (no sign, fits 64 bits), else nothing.
std::optional<std::uint64_t> unsignedValue(const YAML::Node& node);

// "a, b, c".
std::string joinNames(const std::vector<std::string>& names);

// Asset and job names name folders: non-empty, only a-z, 0-9, '_' and '-'.
bool isAssetName(const std::string& name);

}  // namespace rockbake
