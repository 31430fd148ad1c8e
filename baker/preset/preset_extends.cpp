#include "preset/preset_extends.h"

#include <algorithm>
#include <optional>

#include "core/did_you_mean.h"
#include "core/error.h"
#include "platform/data_dir.h"
#include "preset/catalogue.h"
#include "preset/schema.h"
#include "preset/yaml_text.h"

namespace rockbake {
namespace {

namespace fs = std::filesystem;

SourceLocation locationOf(const std::string& file, const YAML::Mark& mark) {
  if (mark.is_null()) return {file, 0, 0};
  return {file, mark.line + 1, mark.column + 1};
}

bool sameFile(const fs::path& a, const fs::path& b) {
  std::error_code error_a, error_b;
  const auto canonical_a = fs::weakly_canonical(a, error_a);
  const auto canonical_b = fs::weakly_canonical(b, error_b);
  return (error_a ? a : canonical_a) == (error_b ? b : canonical_b);
}

// `child_keys`: the keys the preset itself gives in the map at `path`.
bool droppedByMergeRule(const std::vector<std::string>& child_keys, const std::string& path, const std::string& key) {
  const auto contains = [](const std::vector<std::string>& keys, const std::string& k) {
    return std::find(keys.begin(), keys.end(), k) != keys.end();
  };
  for (const auto& rule : schema::mergeRules())
    if (rule.path == path && contains(rule.drops, key))
      for (const auto& given : rule.when_given)
        if (contains(child_keys, given)) return true;
  return false;
}

// Copies the base's keys the child does not have into the child (maps deep-merged, the child's keys win;
// lists and scalars replaced whole; schema::mergeRules()) and records which file each copied key path came from.
void mergeBase(YAML::Node child, const YAML::Node& base, const std::string& path, std::vector<Origin>& origins,
               const std::vector<Origin>& base_origins) {
  std::vector<std::string> child_keys;
  for (const auto& entry : child)
    if (entry.first.IsScalar()) child_keys.push_back(entry.first.Scalar());
  std::vector<std::pair<std::string, YAML::Mark>> seen;
  for (const auto& entry : base) {
    const std::string& base_file = originOf(base_origins, path).file;
    if (!entry.first.IsScalar())
      throw InputError(locationOf(base_file, entry.first.Mark()), path,
                       "expected a key name, found " + describe(entry.first));
    const std::string key = entry.first.Scalar();
    const std::string key_path = path.empty() ? key : path + "." + key;
    // Both of a repeated key would merge into one: report it as loading a single file does.
    const auto first = std::find_if(seen.begin(), seen.end(), [&](const auto& s) { return s.first == key; });
    if (first != seen.end())
      throw InputError(locationOf(originOf(base_origins, key_path).file, entry.first.Mark()), key_path,
                       "'" + key + "' is given twice (first on line " + std::to_string(first->second.line + 1) + ")",
                       "keep one of them");
    seen.emplace_back(key, entry.first.Mark());

    std::optional<YAML::Node> mine;
    for (auto child_entry : child)
      if (child_entry.first.IsScalar() && child_entry.first.Scalar() == key) {
        mine = child_entry.second;
        break;
      }
    if (!mine) {
      if (droppedByMergeRule(child_keys, path, key)) continue;
      child[key] = entry.second;
      origins.push_back({key_path, originOf(base_origins, key_path).file, originOf(base_origins, key_path).folder});
      for (const auto& origin : base_origins)
        if (origin.key_path.size() > key_path.size() && underKeyPath(origin.key_path, key_path))
          origins.push_back(origin);
    } else if (mine->IsMap() && entry.second.IsMap()) {
      mergeBase(*mine, entry.second, key_path, origins, base_origins);
    }
  }
}

// The installed catalogue file `extends: rockbake:NAME` names (preset/catalogue.h); InputError at `here`
// for a name that is not one, or names no installed file.
fs::path catalogueBase(const std::string& name, const SourceLocation& here) {
  if (const auto problem = catalogueNameProblem(name))
    throw InputError(here, "extends", *problem,
                     "rockbake:NAME names a preset installed with rockbake, such as rockbake:base.yaml");
  const fs::path dir = catalogueDir();
  if (dir.empty())
    throw InputError(here, "extends", "cannot find the installed catalogue: rockbake's data folder is unknown",
                     "set ROCKBAKE_DATA_DIR to an installed <prefix>/share/rockbake");
  const fs::path base = (dir / name).lexically_normal();
  std::error_code ec;
  if (fs::is_regular_file(base, ec)) return base;
  const std::vector<std::string> names = cataloguePresetNames();
  std::string hint = names.empty() ? "the catalogue folder is missing or empty: reinstall rockbake, or set "
                                     "ROCKBAKE_DATA_DIR to an installed <prefix>/share/rockbake"
                                   : "installed: " + joinNames(names);
  if (const auto close = closestName(name, names)) hint = "did you mean rockbake:" + *close + "? " + hint;
  throw InputError(here, "extends",
                   "no installed catalogue preset '" + name + "' in " + dir.string() + " (" + dataDirOrigin() + ")",
                   hint);
}

// The base preset `root`'s `extends` names, read and parsed (null when there is none).
// `base_file` and `base_name` receive its absolute path and its name in messages.
YAML::Node readBase(const YAML::Node& root, const std::string& name, const fs::path& file,
                    const std::vector<fs::path>& chain, fs::path& base_file, std::string& base_name) {
  std::optional<YAML::Node> value;
  YAML::Mark key_mark;
  for (const auto& entry : root)
    if (entry.first.IsScalar() && entry.first.Scalar() == "extends") {
      value = entry.second;
      key_mark = entry.first.Mark();
      break;
    }
  if (!value) return YAML::Node();
  const SourceLocation here =
      locationOf(name, value->IsDefined() && !value->IsNull() && !value->Mark().is_null() ? value->Mark() : key_mark);
  if (!value->IsScalar() || value->Scalar().empty())
    throw InputError(here, "extends", "expected the path of a base preset, found " + describe(*value),
                     "for example extends: base.yaml (relative to this file), or rockbake:base.yaml (installed)");
  const fs::path written = value->Scalar();
  if (const auto catalogue = catalogueName(value->Scalar())) {
    base_file = catalogueBase(*catalogue, here);
    base_name = base_file.string();
  } else {
    base_file = (written.is_absolute() ? written : file.parent_path() / written).lexically_normal();
    base_name = written.is_absolute() ? written.string()
                                      : (fs::path(name).parent_path() / written).lexically_normal().string();
  }

  for (const auto& earlier : chain)
    if (sameFile(earlier, base_file)) {
      std::string cycle;
      for (const auto& f : chain) cycle += f.lexically_relative(chain.front().parent_path()).string() + " → ";
      cycle += base_file.lexically_relative(chain.front().parent_path()).string();
      throw InputError(here, "extends", "the base presets form a cycle: " + cycle, "remove one of these extends");
    }

  const std::optional<std::string> text = readYamlFile(base_file.string(), "a preset");
  if (!text)
    throw InputError(here, "extends", "no base preset at " + base_file.string(),
                     "extends paths are relative to the folder of " + name);
  YAML::Node base;
  try {
    base = loadYamlDocument(*text, base_name, "a preset");
  } catch (const InputError& e) {
    throw InputError(here, "extends", "cannot use the base preset: " + std::string(e.what()));
  }
  if (!base.IsMap())
    throw InputError(here, "extends", "the base preset " + base_name + " is not a YAML map (key: value, ...)");
  return base;
}

}  // namespace

void resolveExtends(YAML::Node root, const std::string& name, const fs::path& file, std::vector<fs::path>& chain,
                    std::vector<Origin>& origins) {
  origins = {{"", name, file.parent_path()}};
  chain.push_back(file);
  fs::path base_file;
  std::string base_name;
  YAML::Node base = readBase(root, name, file, chain, base_file, base_name);
  if (!base.IsDefined() || base.IsNull()) return;
  std::vector<Origin> base_origins;
  resolveExtends(base, base_name, base_file, chain, base_origins);
  root.remove("extends");
  mergeBase(root, base, "", origins, base_origins);
}

}  // namespace rockbake
