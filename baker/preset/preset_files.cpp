#include "preset/preset_files.h"

#include <algorithm>

#include "preset/catalogue.h"
#include "preset/preset_tree.h"
#include "preset/schema_spec.h"
#include "preset/yaml_text.h"

namespace rockbake {
namespace {

namespace fs = std::filesystem;

std::string joinPath(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

// Every path key under `map` (at `prefix`), entering maps and lists of maps; a map met again
// inside itself (a bubble collection's bubbles) is not entered twice.
void collectPathKeys(const schema::MapInfo& map, const std::string& prefix,
                     std::vector<const schema::MapInfo*>& open, std::vector<std::string>& out) {
  open.push_back(&map);
  for (const schema::KeyInfo& key : map.keys) {
    if (!key.name.empty() && key.type == "path") out.push_back(joinPath(prefix, key.name));
    if (!key.map) continue;
    const schema::MapInfo& inner = key.map();
    if (std::find(open.begin(), open.end(), &inner) != open.end()) continue;
    const std::string path = key.name.empty() ? prefix : joinPath(prefix, key.name);
    collectPathKeys(inner, key.list ? joinPath(path, "[]") : path, open, out);
  }
  open.pop_back();
}

std::vector<std::string> splitPattern(const std::string& pattern) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (true) {
    const std::size_t dot = pattern.find('.', start);
    parts.push_back(pattern.substr(start, dot - start));
    if (dot == std::string::npos) return parts;
    start = dot + 1;
  }
}

// The scalars at `parts` (from `i`) under `node`, with their key paths.
void findScalars(const YAML::Node& node, const std::vector<std::string>& parts, std::size_t i,
                 const std::string& path, std::vector<std::pair<std::string, YAML::Node>>& out) {
  if (i == parts.size()) {
    if (node.IsScalar()) out.emplace_back(path, node);
    return;
  }
  if (parts[i] == "[]") {
    if (node.IsSequence())
      for (std::size_t j = 0; j < node.size(); ++j)
        findScalars(node[j], parts, i + 1, joinPath(path, std::to_string(j)), out);
    return;
  }
  if (!node.IsMap()) return;
  for (const auto& entry : node)
    if (entry.first.IsScalar() && entry.first.Scalar() == parts[i])
      findScalars(entry.second, parts, i + 1, joinPath(path, parts[i]), out);
}

// The top-level `extends` of one file's own YAML, or null.
YAML::Node ownExtends(const fs::path& file, const std::string& name) {
  const YAML::Node root = loadYamlDocument(readPresetFile(file), name, "a preset");
  if (root.IsMap())
    for (const auto& entry : root)
      if (entry.first.IsScalar() && entry.first.Scalar() == "extends") return entry.second;
  return YAML::Node();
}

SourceLocation locationOf(const std::string& name, const YAML::Node& node) {
  const YAML::Mark mark = node.Mark();
  if (mark.is_null()) return {name};
  return {name, mark.line + 1, mark.column + 1};
}

// The chain's `extends` values, and the name messages give each file (as the loader names them).
void addExtends(const fs::path& preset, PresetFiles& files, std::vector<std::string>& names) {
  names.push_back(preset.string());
  for (std::size_t i = 0; i + 1 < files.chain.size(); ++i) {
    const YAML::Node value = ownExtends(files.chain[i], names[i]);
    PresetFileRef ref;
    ref.from = files.chain[i];
    ref.where = locationOf(names[i], value);
    ref.offset = value.Mark().is_null() ? 0 : std::size_t(value.Mark().pos);
    ref.key_path = "extends";
    ref.written = value.IsScalar() ? value.Scalar() : std::string();
    ref.target = files.chain[i + 1];
    ref.catalogue = catalogueName(ref.written).has_value();
    const fs::path written(ref.written);
    names.push_back(ref.catalogue || written.is_absolute()
                        ? ref.target.string()
                        : (fs::path(names[i]).parent_path() / written).lexically_normal().string());
    files.refs.push_back(std::move(ref));
  }
}

}  // namespace

std::vector<std::string> pathKeyPatterns() {
  std::vector<std::string> patterns;
  std::vector<const schema::MapInfo*> open;
  collectPathKeys(schema::presetTable().info, "", open, patterns);
  patterns.erase(std::remove(patterns.begin(), patterns.end(), "extends"), patterns.end());
  return patterns;
}

PresetFiles presetFiles(const fs::path& preset) {
  const PresetTree tree = readPresetTree(readPresetFile(preset), preset, {});
  PresetFiles files;
  files.chain = tree.files;
  std::vector<std::string> names;
  addExtends(preset, files, names);
  for (const auto& pattern : pathKeyPatterns()) {
    std::vector<std::pair<std::string, YAML::Node>> values;
    findScalars(tree.root, splitPattern(pattern), 0, "", values);
    for (const auto& [key_path, node] : values) {
      const Origin& origin = originOf(tree.source.origins, key_path);
      const auto from = std::find_if(files.chain.begin(), files.chain.end(), [&](const fs::path& f) {
        return f.parent_path() == origin.folder && f.filename() == fs::path(origin.file).filename();
      });
      PresetFileRef ref;
      ref.from = from != files.chain.end() ? *from : files.chain.front();
      ref.where = locationOf(names[std::size_t(from != files.chain.end() ? from - files.chain.begin() : 0)], node);
      ref.offset = node.Mark().is_null() ? 0 : std::size_t(node.Mark().pos);
      ref.key_path = key_path;
      ref.written = node.Scalar();
      const fs::path given(ref.written);
      ref.target = fs::absolute(given.is_absolute() ? given : origin.folder / given).lexically_normal();
      files.refs.push_back(std::move(ref));
    }
  }
  return files;
}

}  // namespace rockbake
