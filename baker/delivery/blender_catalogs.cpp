#include "delivery/blender_catalogs.h"

#include <algorithm>
#include <set>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/sha256.h"

namespace rockbake {

namespace {

bool endsWith(const std::string& text, const std::string& tail) {
  return text.size() > tail.size() && text.compare(text.size() - tail.size(), tail.size(), tail) == 0;
}

// A catalogue path component: the characters asset names are made of (a-z 0-9 _ -), anything else
// as '-', so that no ':', '/' or line break from a hand-edited manifest reaches the catalogue file.
std::string component(const std::string& text) {
  std::string out;
  for (const char c : text.substr(0, 64))
    out += (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || c == '-' ? c : '-';
  return out.empty() ? "rockbake" : out;
}

std::string stringOr(const nlohmann::json& object, const char* key) {
  if (!object.is_object()) return {};
  const auto it = object.find(key);
  return it != object.end() && it->is_string() ? it->get<std::string>() : std::string();
}

}  // namespace

std::string catalogPathForJob(const nlohmann::json& inputs) {
  const nlohmann::json job = inputs.is_object() ? inputs.value("job", nlohmann::json::object()) : nlohmann::json();
  std::string name = stringOr(job, "name");
  const bool in_library = inputs.is_object() && inputs.contains("library") && !inputs["library"].is_null();
  if (!in_library) return component(name);
  // A library job is named <entry>-<wedge>-s<seed> (docs/libraries.md): take the suffixes off.
  if (job.contains("seed") && job["seed"].is_number_integer() && job["seed"] >= 0) {
    const std::string seed = "-s" + std::to_string(job["seed"].get<std::uint64_t>());
    if (endsWith(name, seed)) name.resize(name.size() - seed.size());
  }
  const std::string wedge = stringOr(job, "wedge");
  if (!wedge.empty() && endsWith(name, "-" + wedge)) name.resize(name.size() - wedge.size() - 1);
  return wedge.empty() ? component(name) : component(name) + "/" + component(wedge);
}

std::string catalogUuid(const std::string& path) {
  std::string hex = sha256Hex("rockbake blender catalogue:" + path).substr(0, 32);
  hex[12] = '8';  // version 8: a custom, name-derived UUID (RFC 9562)
  static const char kVariant[] = "89ab";
  hex[16] = kVariant[std::stoi(hex.substr(16, 1), nullptr, 16) & 3];  // variant 10xx
  return fmt::format("{}-{}-{}-{}-{}", hex.substr(0, 8), hex.substr(8, 4), hex.substr(12, 4), hex.substr(16, 4),
                     hex.substr(20, 12));
}

BlenderCatalog blenderCatalog(const std::string& path) {
  std::string simple = path;
  std::replace(simple.begin(), simple.end(), '/', '-');
  return {path, catalogUuid(path), simple};
}

std::vector<BlenderCatalog> catalogsWithParents(const std::vector<std::string>& paths) {
  std::set<std::string> all;
  for (const auto& path : paths)
    for (std::size_t slash = path.find('/'); slash != std::string::npos; slash = path.find('/', slash + 1))
      all.insert(path.substr(0, slash));
  all.insert(paths.begin(), paths.end());
  std::vector<BlenderCatalog> catalogs;
  for (const auto& path : all) catalogs.push_back(blenderCatalog(path));
  return catalogs;
}

std::string catalogFileText(const std::vector<BlenderCatalog>& catalogs) {
  std::string text =
      "# This is an Asset Catalog Definition file for Blender.\n"
      "#\n"
      "# Empty lines and lines starting with `#` will be ignored.\n"
      "# The first non-ignored line should be the version indicator.\n"
      "# Other lines are of the format \"UUID:catalog/path/for/assets:simple catalog name\"\n"
      "#\n"
      "# Written by rockbake blender-library: one catalogue per preset (and per wedge), each UUID\n"
      "# derived from its path, so every run writes the same file (docs/libraries.md).\n"
      "\n"
      "VERSION 1\n"
      "\n";
  for (const auto& c : catalogs) text += c.uuid + ":" + c.path + ":" + c.simple_name + "\n";
  return text;
}

}  // namespace rockbake
