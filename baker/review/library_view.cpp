#include "review/library_view.h"

#include <fstream>
#include <sstream>
#include <stdexcept>

namespace rockbake {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

// A JSON file of the library, or null when it is missing or unreadable (a
// damaged asset is shown as the index says, not refused).
json readJsonOrNull(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return nullptr;
  std::stringstream text;
  text << in.rdbuf();
  json j = json::parse(text.str(), nullptr, false);
  return j.is_discarded() ? json(nullptr) : j;
}

json fileLink(const std::string& relative) {
  return "/files/" + relative;
}

json linkOrNull(const json& entry, const char* key) {
  return entry.contains(key) && entry[key].is_string() ? fileLink(entry[key].get<std::string>()) : json(nullptr);
}

json jobValue(const json& entry, const char* key) {
  const json& job = entry.contains("job") && entry["job"].is_object() ? entry["job"] : json::object();
  return job.contains(key) ? job[key] : json(nullptr);
}

json summary(const json& entry, const json& verdicts, const json& asset, const json& manifest) {
  const std::string name = entry.value("name", "");
  json s = {{"name", name}, {"status", entry.value("status", "")}};
  s["message"] = entry.contains("message") ? entry["message"] : json(nullptr);
  s["preset"] = jobValue(entry, "preset");
  s["wedge"] = jobValue(entry, "wedge");
  const json seed = jobValue(entry, "seed");
  s["seed"] = !seed.is_null()                                       ? seed
              : manifest.is_object() && manifest.contains("inputs") ? manifest["inputs"].value("seed", json(nullptr))
                                                                    : json(nullptr);
  s["tags"] = asset.is_object() ? asset.value("tags", json::array()) : json::array();
  const json lods = asset.is_object() ? asset.value("lods", json::array()) : json::array();
  s["triangles"] = !lods.empty() ? lods[0].value("triangles", json(nullptr)) : json(nullptr);
  s["size_m"] = asset.is_object() ? asset.value("size_m", json(nullptr)) : json(nullptr);
  // LOD0's pixels per metre, with a texture set (docs/formats.md, asset.json's lods).
  s["texel_density"] = !lods.empty() ? lods[0].value("texel_density", json(nullptr)) : json(nullptr);
  json seconds = nullptr;
  if (manifest.is_object() && manifest.contains("timings") && manifest["timings"].contains("stages"))
    seconds = manifest["timings"]["stages"].value("total", json(nullptr));
  s["bake_seconds"] = seconds;
  s["input_hash"] = entry.value("input_hash", "");
  json files = {{"render", linkOrNull(entry, "render")},   {"movie", linkOrNull(entry, "movie")},
                {"asset", linkOrNull(entry, "asset")},     {"manifest", linkOrNull(entry, "manifest")},
                {"failure", linkOrNull(entry, "failure")}, {"lods", json::array()}};
  for (const json& lod : lods)
    if (lod.contains("file") && lod["file"].is_string())
      files["lods"].push_back({{"level", lod.value("level", 0)},
                               {"file", fileLink(name + "/" + lod["file"].get<std::string>())},
                               {"triangles", lod.value("triangles", 0)}});
  s["files"] = files;
  if (verdicts.contains(name) && verdicts[name].is_object()) {
    const json& v = verdicts[name];
    s["review"] = {{"status", v.value("status", "")},
                   {"note", v.value("note", "")},
                   {"updated", v.value("updated", "")},
                   {"stale", v.value("input_hash", "") != s["input_hash"].get<std::string>()}};
  } else {
    s["review"] = nullptr;
  }
  return s;
}

bool isFinished(const json& entry) {
  const std::string status = entry.value("status", "");
  return status == "ok" || status == "skipped-resumed";
}

}  // namespace

json libraryIndexAssets(const fs::path& dir) {
  const fs::path file = dir / "index.json";
  if (!fs::is_regular_file(file))
    throw std::runtime_error(file.string() +
                             " not found: review serves a baked library; bake one first with "
                             "`rockbake library LIBRARY.yaml -o " +
                             dir.string() + "`");
  const json index = readJsonOrNull(file);
  if (!index.is_object() || !index.contains("assets") || !index["assets"].is_array())
    throw std::runtime_error(file.string() +
                             " is not a library index (no \"assets\" list); write it again with "
                             "`rockbake library LIBRARY.yaml -o " +
                             dir.string() + " --index-only`");
  return index["assets"];
}

json assetSummaries(const fs::path& dir, const json& verdicts) {
  json out = json::array();
  for (const json& entry : libraryIndexAssets(dir)) {
    if (!entry.is_object() || !entry.contains("name") || !entry["name"].is_string()) continue;
    const std::string name = entry["name"];
    const bool finished = isFinished(entry);
    out.push_back(summary(entry, verdicts, finished ? readJsonOrNull(dir / name / "asset.json") : json(nullptr),
                          finished ? readJsonOrNull(dir / name / "manifest.json") : json(nullptr)));
  }
  return out;
}

std::optional<json> assetDetail(const fs::path& dir, const std::string& name, const json& verdicts) {
  for (const json& entry : libraryIndexAssets(dir)) {
    if (!entry.is_object() || entry.value("name", "") != name) continue;
    const bool finished = isFinished(entry);
    const json asset = finished ? readJsonOrNull(dir / name / "asset.json") : json(nullptr);
    const json manifest = finished ? readJsonOrNull(dir / name / "manifest.json") : json(nullptr);
    const json stats = finished ? readJsonOrNull(dir / name / "stats.json") : json(nullptr);
    json d = summary(entry, verdicts, asset, manifest);
    d["asset"] = asset;
    d["lods"] = asset.is_object() ? asset.value("lods", json::array()) : json::array();
    d["stages"] = stats.is_object() ? stats.value("stages", json(nullptr)) : json(nullptr);
    d["bake_preset"] = stats.is_object() ? stats.value("preset", json(nullptr)) : json(nullptr);
    d["job"] = entry.contains("job") ? entry["job"] : json(nullptr);
    return d;
  }
  return std::nullopt;
}

}  // namespace rockbake
