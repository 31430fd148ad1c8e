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
// "a, b and c" (conjunction "and"), "a, b or c".
std::string joinNamesWith(const std::vector<std::string>& names, const std::string& conjunction);

// Asset and job names name folders: non-empty, only a-z, 0-9, '_' and '-',
// at most kMaxNameLength characters.
inline constexpr std::size_t kMaxNameLength = 64;
bool isAssetName(const std::string& name);
// Why `name` is not an asset name ("'Big Rock' may only use a-z, 0-9, '_' and
// '-'", "'aaa…' is 300 characters long; at most 64"), or nothing when it is one.
std::optional<std::string> assetNameProblem(const std::string& name);

// Limits on the YAML files rockbake reads (presets, library files), checked
// before they are parsed: yaml-cpp needs about 160 bytes of memory per byte.
inline constexpr std::uintmax_t kMaxYamlFileBytes = std::uintmax_t(1) << 20;

// The one YAML document of a file's text (null when the text is empty);
// `file` names it in messages, `what` says what it is ("a preset"). Throws
// InputError at the place of the first problem: a control byte (YAML allows
// only tab, line feed and carriage return; the byte is shown escaped), nesting
// deeper than yaml-cpp reads, malformed YAML, or a second document.
YAML::Node loadYamlDocument(const std::string& text, const std::string& file, const std::string& what);

// The bytes of a YAML input file, or nothing when it is not a readable regular
// file. Throws InputError (naming `file`) when it is larger than
// kMaxYamlFileBytes; `what` says what the file is ("a preset").
std::optional<std::string> readYamlFile(const std::string& file, const std::string& what);

}  // namespace rockbake
