#include "preset/preset_overrides.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <limits>
#include <sstream>

#include "preset/preset.h"
#include "preset/schema.h"

namespace rockbake {
namespace {

std::vector<std::string> keyPathParts(const std::string& path, const auto& bad) {
  std::vector<std::string> keys;
  std::stringstream stream(path);
  for (std::string key; std::getline(stream, key, '.');) {
    if (key.empty()) bad("the key path has an empty part", "");
    keys.push_back(key);
  }
  if (keys.empty()) bad("the key path is empty", "");
  return keys;
}

// `origin` is what messages name as the override's location: "--set <argument>" by default.
void applyOverride(YAML::Node& root, const std::string& argument, const std::string& origin, Source& source) {
  const auto bad = [&](const std::string& problem, const std::string& hint) {
    throw InputError({origin.empty() ? "--set" : origin}, "", "'" + argument + "': " + problem, hint);
  };
  const std::size_t equals = argument.find('=');
  if (equals == std::string::npos || equals == 0)
    bad("expected key.path=VALUE", "for example --set colluvium.yield=0.3 or --set bubbles.0.spheroidal=0.5");
  const std::string path = argument.substr(0, equals);
  YAML::Node value;
  try {
    value = YAML::Load(argument.substr(equals + 1));
  } catch (const YAML::Exception& e) {
    bad("the value is not valid YAML: " + e.msg, "");
  }
  const std::vector<std::string> keys = keyPathParts(path, bad);

  YAML::Node node;
  node.reset(root);
  for (std::size_t i = 0; i < keys.size(); ++i) {
    const std::string& key = keys[i];
    const bool last = i + 1 == keys.size();
    YAML::Node next;
    if (node.IsSequence()) {
      const bool digits = std::all_of(key.begin(), key.end(), [](unsigned char c) { return std::isdigit(c); });
      std::size_t index = std::numeric_limits<std::size_t>::max();
      if (!digits) bad("'" + key + "' must be a list index (0, 1, ...) at that point", "");
      try {
        index = std::stoul(key);
      } catch (const std::out_of_range&) {
        // leave it past the end
      }
      if (index >= node.size())
        bad("index " + key + " is past the end of a list of " + std::to_string(node.size()), "");
      if (last) {
        node[index] = value;
        break;
      }
      next.reset(node[index]);
    } else {
      if (!node.IsMap() && !node.IsNull()) bad("'" + key + "' cannot be set inside a value that is not a map", "");
      if (last) {
        node[key] = value;
        // Choosing one of a set of alternatives (`cycles` for `time`) replaces the others.
        for (const auto& other : schema::siblingsReplacedBy(path)) node.remove(other);
        break;
      }
      if (!node[key].IsDefined() || node[key].IsNull()) node[key] = YAML::Node(YAML::NodeType::Map);
      next.reset(node[key]);
    }
    node.reset(next);
  }
  source.overrides.emplace_back(path, origin.empty() ? "--set " + argument : origin);
}

// The value of the scalar at `root[block][key]` as an int, or `fallback` when it is missing or
// not a whole number (the reader reports those later, at the key).
int scalarOr(const YAML::Node& root, const char* block, const char* key, int fallback) {
  const YAML::Node parent = root[block];
  if (!parent.IsDefined() || !parent.IsMap()) return fallback;
  const YAML::Node value = parent[key];
  if (!value.IsDefined() || !value.IsScalar()) return fallback;
  try {
    return value.as<int>();
  } catch (const YAML::Exception&) {
    return fallback;
  }
}

// Maps follow --resolution (docs/textures.md §8): a preview at a coarser grid than the
// preset's keeps the preset's texels per voxel instead of its texel count. `own` is the
// preset's grid.resolution before the override.
void followResolution(YAML::Node& root, const PresetOverrides& overrides, int own, Source& source) {
  if (!root["texture"].IsDefined() || !root["texture"].IsMap())
    return;  // no texture set, or a malformed block the reader names
  const bool set_by_hand = std::any_of(overrides.sets.begin(), overrides.sets.end(), [](const std::string& s) {
    return s.rfind("texture.size=", 0) == 0 || s.rfind("texture=", 0) == 0;
  });
  const int size = scalarOr(root, "texture", "size", TextureParams{}.size);
  const int scaled = mapSizeAtResolution(size, own, *overrides.resolution);
  if (set_by_hand || scaled == size) return;
  root["texture"]["size"] = scaled;
  source.overrides.emplace_back(
      "texture.size", "--resolution " + std::to_string(*overrides.resolution) + " (maps follow the resolution)");
}

// Stones keep their size under --resolution (docs/model.md §13): clasts.size is in voxels, so a
// preview at a coarser grid than the preset's would make every stone larger; it is scaled to keep
// the preset's world size (within the key's range), unless the command line gave it.
void stonesFollowResolution(YAML::Node& root, const PresetOverrides& overrides, int own, Source& source) {
  if (!root["clasts"].IsDefined() || !root["clasts"].IsMap() || own <= 0 || *overrides.resolution == own) return;
  const bool set_by_hand = std::any_of(overrides.sets.begin(), overrides.sets.end(), [](const std::string& s) {
    return s.rfind("clasts.size=", 0) == 0 || s.rfind("clasts=", 0) == 0;
  });
  if (set_by_hand) return;
  std::array<double, 2> size = ClastParams{}.size;
  const YAML::Node given = root["clasts"]["size"];
  if (given.IsDefined() && !given.IsNull()) {
    if (!given.IsSequence() || given.size() != 2) return;  // malformed: the reader names it
    try {
      size = {given[0].as<double>(), given[1].as<double>()};
    } catch (const YAML::Exception&) {
      return;
    }
  }
  const double factor = double(*overrides.resolution) / own;
  YAML::Node scaled(YAML::NodeType::Sequence);
  scaled.SetStyle(YAML::EmitterStyle::Flow);
  for (const double s : size) scaled.push_back(std::clamp(s * factor, 0.5, 64.0));
  root["clasts"]["size"] = scaled;
  source.overrides.emplace_back("clasts.size",
                                "--resolution " + std::to_string(*overrides.resolution) + " (stones keep their size)");
}

}  // namespace

int mapSizeAtResolution(int size, int own_resolution, int resolution) {
  if (own_resolution <= 0 || resolution >= own_resolution) return size;
  const double wanted = double(size) * resolution / own_resolution;
  int scaled = kMinFollowedMapSize;
  while (scaled < wanted && scaled < size) scaled *= 2;
  return std::min(scaled, size);
}

void applyOverrides(YAML::Node& root, const PresetOverrides& overrides, Source& source) {
  for (std::size_t i = 0; i < overrides.sets.size(); ++i)
    applyOverride(root, overrides.sets[i], i < overrides.set_origins.size() ? overrides.set_origins[i] : "", source);
  if (overrides.seed) {
    root["seed"] = *overrides.seed;
    source.overrides.emplace_back("seed", "--seed " + std::to_string(*overrides.seed));
  }
  if (overrides.resolution) {
    const int own = scalarOr(root, "grid", "resolution", GridParams{}.resolution);
    followResolution(root, overrides, own, source);
    stonesFollowResolution(root, overrides, own, source);
    if (!root["grid"].IsDefined() || root["grid"].IsNull()) root["grid"] = YAML::Node(YAML::NodeType::Map);
    if (root["grid"].IsMap()) root["grid"]["resolution"] = *overrides.resolution;
    source.overrides.emplace_back("grid.resolution", "--resolution " + std::to_string(*overrides.resolution));
  }
}

}  // namespace rockbake
