// docs/preset-reference.md's key tables, written from the schema's table
// (preset/schema.cpp): "The file" for the top level, then one section per
// top-level map, every key by its full path (each item of a list as
// `bubbles.[].up_to`), with the notes the table gives its maps.
#include <sstream>

#include "preset/schema.h"
#include "preset/schema_spec.h"

namespace rockbake::schema {
namespace {

std::string join(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

// A default as a preset would write it: [4, 4, 6], studio, 0.15.
std::string yamlText(const json& j) {
  if (j.is_string()) return j.get<std::string>();
  if (j.is_number_float()) return formatNumber(j.get<double>());
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
    if (at == 0 || text[at - 1] != '\\') text.replace(at, 1, "\\|");
  return text;
}

struct Row {
  std::string path, type, unit, range, default_text, meaning;
};

// Where a map's keys are listed: its path, the block a required key is required in ("variation", or
// empty where the map itself must be given), and what keys written inline for an optional struct
// default to.
struct Place {
  std::string path, required_in, inline_default;
};

class Reference {
 public:
  Reference() : keyframed_(keyframedKeys()), resumable_(resumableKeys()) {}

  std::string write() const {
    const MapInfo& root = presetTable().info;
    std::ostringstream out;
    std::vector<std::string> notes;
    out << "## The file\n\n";
    std::vector<Row> rows;
    for (const KeyInfo& key : root.keys) rows.push_back(rowOf(key, root, {key.name, "", ""}));
    table(out, rows);
    out << "\n" << root.note << "\n";
    for (const KeyInfo& key : root.keys) {
      if (!key.map || !key.see.empty()) continue;
      const MapInfo& map = key.map();
      out << "\n## `" << key.name << "`\n\n";
      if (!map.note.empty()) out << map.note << "\n\n";
      std::vector<std::string> later;
      table(out, rowsUnder(map, {key.name + (key.list ? ".[]" : ""), blockOf(key), ""}, later));
      for (const auto& note : later) out << "\n" << note << "\n";
    }
    return out.str();
  }

 private:
  // The block a required key below `key` is required in: the key's own name where it may be left out.
  static std::string blockOf(const KeyInfo& key) {
    return key.presence == Presence::Optional && !key.list ? key.name : "";
  }

  std::string defaultOf(const KeyInfo& key, const MapInfo& map, const Place& place) const {
    if (key.presence != Presence::Optional)
      return key.kind ? "" : place.required_in.empty() ? "required" : "required in `" + place.required_in + "`";
    for (const auto& group : map.alternatives)
      if (!group.kind && group.has(key.name))
        return group.names.front() == key.name ? "required, or `" + group.names.back() + "`"
                                               : "instead of `" + group.names.front() + "`";
    if (!key.default_text.empty()) return key.default_text;
    if (!place.inline_default.empty()) return place.inline_default;
    if (key.map && !key.list && key.see.empty()) return "";
    const std::optional<json> value = key.default_json ? key.default_json() : std::nullopt;
    return !value || value->is_null() ? "none" : "`" + yamlText(*value) + "`";
  }

  Row rowOf(const KeyInfo& key, const MapInfo& map, const Place& place) const {
    const bool here = key.see.empty();  // else the key it is the same as says the unit and range
    Row row{"`" + place.path + "`",     here ? key.type : "as `" + key.see + "`",
            here ? key.unit : "",       here ? key.range : "",
            defaultOf(key, map, place), key.doc};
    if (std::find(keyframed_.begin(), keyframed_.end(), place.path) != keyframed_.end())
      row.meaning += ". *Studio, and resume as a keyframe.*";
    if (std::find(resumable_.begin(), resumable_.end(), place.path) != resumable_.end()) row.meaning += ". *Resume.*";
    return row;
  }

  // The rows of every key under `map`, depth first. A map's own row is left out where its keys say it
  // all (a kind, an optional block); `later` collects the notes of the maps entered.
  std::vector<Row> rowsUnder(const MapInfo& map, const Place& place, std::vector<std::string>& later) const {
    std::vector<Row> rows;
    const auto append = [&](const std::vector<Row>& more) { rows.insert(rows.end(), more.begin(), more.end()); };
    for (const KeyInfo& key : map.keys) {
      if (key.name.empty() && !key.see.empty()) {  // keys written inline as another map's: named, not repeated
        for (KeyInfo inner : key.map().keys) {
          inner.see = join(key.see, inner.name);
          rows.push_back(rowOf(inner, map, {join(place.path, inner.name), place.required_in, key.default_text}));
        }
        continue;
      }
      if (key.name.empty()) {
        append(rowsUnder(key.map(), {place.path, place.required_in, key.default_text}, later));
        continue;
      }
      const std::string path = join(place.path, key.name);
      const bool entered = key.map && key.see.empty();
      const bool own_row = !entered || key.list || (key.presence != Presence::Optional && !key.kind);
      if (own_row) rows.push_back(rowOf(key, map, {path, place.required_in, place.inline_default}));
      if (!entered) continue;
      if (!key.map().note.empty()) later.push_back(key.map().note);
      append(rowsUnder(key.map(), {path + (key.list ? ".[]" : ""), key.kind ? place.required_in : blockOf(key), ""},
                       later));
    }
    return rows;
  }

  static void table(std::ostringstream& out, const std::vector<Row>& rows) {
    out << "| key | type | unit | range | default | meaning |\n|---|---|---|---|---|---|\n";
    for (const Row& r : rows)
      out << "| " << r.path << " | " << escapeCell(r.type) << " | " << r.unit << " | " << escapeCell(r.range) << " | "
          << escapeCell(r.default_text) << " | " << escapeCell(r.meaning) << " |\n";
  }

  std::vector<std::string> keyframed_, resumable_;
};

}  // namespace

std::string presetReferenceTables() {
  return Reference().write();
}

}  // namespace rockbake::schema
