// docs/preset-reference.md's key tables, written from the schema's table
// (preset/schema.cpp): one table for the top level, then one per top-level
// block, every key by its full path (list items as `bubbles[].up_to`). A map
// used in several places (a bubble, a noise) is listed where it first appears,
// nearest the top, and named from the others.
#include <deque>
#include <map>
#include <set>
#include <sstream>

#include "preset/schema.h"
#include "preset/schema_spec.h"

namespace rockbake::schema {
namespace {

std::string join(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

// A default as a preset would write it: [4.0, 4.0, 6.0], studio, none.
std::string yamlText(const json& j) {
  if (j.is_null()) return "none";
  if (j.is_string()) return j.get<std::string>();
  std::string out;
  if (j.is_array()) {
    for (const auto& item : j) out += (out.empty() ? "" : ", ") + yamlText(item);
    return "[" + out + "]";
  }
  if (j.is_object()) {
    for (const auto& [key, value] : j.items()) out += (out.empty() ? "" : ", ") + key + ": " + yamlText(value);
    return "{" + out + "}";
  }
  return j.dump();
}

std::string escapeCell(std::string text) {
  for (std::size_t at = text.find('|'); at != std::string::npos; at = text.find('|', at + 2))
    text.replace(at, 1, "\\|");
  return text;
}

class Reference {
 public:
  Reference() {
    for (const auto& key : keyframedKeys()) keyframed_.insert(key);
    for (const auto& key : resumableKeys()) resumable_.insert(key);
    claimMaps();
  }

  std::string write() const {
    const MapInfo& root = presetTable().info;
    std::ostringstream out;
    out << "### Top level\n\n";
    table(out, rowsUnder(root, "", nullptr));
    notes(out, {{"", &root}});
    for (const KeyInfo& key : root.keys) {
      if (!key.map) continue;
      const std::string path = key.name + (key.list ? "[]" : "");
      std::vector<std::pair<std::string, const MapInfo*>> maps;
      out << "\n### `" << key.name << "`\n\n";
      table(out, rowsUnder(key.map(), path, &maps));
      notes(out, maps);
    }
    return out.str();
  }

 private:
  struct Row {
    std::string path, value, unit, default_text, doc;
  };

  // Each map is documented at the path nearest the top where it appears (breadth first; keys written
  // inline count as their map's own).
  void claimMaps() {
    std::deque<std::pair<const MapInfo*, std::string>> queue = {{&presetTable().info, ""}};
    while (!queue.empty()) {
      const auto [map, path] = queue.front();
      queue.pop_front();
      claimChildren(*map, path, queue);
    }
  }
  void claimChildren(const MapInfo& map, const std::string& path,
                     std::deque<std::pair<const MapInfo*, std::string>>& queue) {
    for (const KeyInfo& key : map.keys) {
      if (key.name.empty()) {
        claimChildren(key.map(), path, queue);
        continue;
      }
      const std::string child = join(path, key.name) + (key.list ? "[]" : "");
      if (key.map && claimed_.emplace(&key.map(), child).second) queue.emplace_back(&key.map(), child);
    }
  }

  Row rowOf(const KeyInfo& key, const std::string& path) const {
    Row row{"`" + path + "`", key.value, key.unit, "", key.doc};
    if (key.map) {
      const std::string& home = claimed_.at(&key.map());
      if (home != path + (key.list ? "[]" : "")) row.value += ", as `" + home + "`";
    }
    if (key.presence != Presence::Optional)
      row.default_text = key.kind ? "" : "required";
    else if (!key.default_text.empty())
      row.default_text = key.default_text;
    else if (key.default_json && !(key.map && !key.list))
      row.default_text = yamlText(key.default_json().value_or(json(nullptr)));
    if (keyframed_.count(path)) row.doc += ". *Studio; resume (as a keyframe).*";
    if (resumable_.count(path)) row.doc += ". *Resume.*";
    return row;
  }

  // The rows of `map`'s keys at `path`, depth first: inline keys in place, each map entered at its home
  // when `maps` is given (which collects the maps entered, for their notes). `inline_default` stands for
  // the defaults of keys written inline for an optional struct.
  std::vector<Row> rowsUnder(const MapInfo& map, const std::string& path,
                             std::vector<std::pair<std::string, const MapInfo*>>* maps,
                             const std::string& inline_default = {}) const {
    if (maps) maps->emplace_back(path, &map);
    std::vector<Row> rows;
    for (const KeyInfo& key : map.keys) {
      if (key.name.empty()) {
        const auto inner = rowsUnder(key.map(), path, maps, key.default_text);
        rows.insert(rows.end(), inner.begin(), inner.end());
        continue;
      }
      const std::string key_path = join(path, key.name);
      rows.push_back(rowOf(key, key_path));
      if (!inline_default.empty() && !rows.back().default_text.empty()) rows.back().default_text = inline_default;
      const std::string child = key_path + (key.list ? "[]" : "");
      if (maps && key.map && claimed_.at(&key.map()) == child) {
        const auto inner = rowsUnder(key.map(), child, maps);
        rows.insert(rows.end(), inner.begin(), inner.end());
      }
    }
    return rows;
  }

  static void table(std::ostringstream& out, const std::vector<Row>& rows) {
    out << "| key | value | unit | default | meaning |\n|---|---|---|---|---|\n";
    for (const Row& r : rows)
      out << "| " << r.path << " | " << escapeCell(r.value) << " | " << r.unit << " | " << escapeCell(r.default_text)
          << " | " << escapeCell(r.doc) << " |\n";
  }

  static void notes(std::ostringstream& out, const std::vector<std::pair<std::string, const MapInfo*>>& maps) {
    bool any = false;
    for (const auto& [path, map] : maps)
      if (!map->note.empty()) {
        out << (any ? "" : "\n") << "- " << (path.empty() ? "" : "`" + path + "`: ") << map->note << "\n";
        any = true;
      }
  }

  std::map<const MapInfo*, std::string> claimed_;
  std::set<std::string> keyframed_, resumable_;
};

}  // namespace

std::string presetReferenceTables() {
  return Reference().write();
}

}  // namespace rockbake::schema
