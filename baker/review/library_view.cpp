#include "review/library_view.h"

#include "core/error.h"
#include "preset/yaml_text.h"
#include "review/library_json.h"
#include "review/review_store.h"

namespace rockbake {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

// Typed reads of files anyone may have edited: a key that is missing or of
// another type reads as null (or the fallback), never as an error.
json member(const json& object, const char* key) {
  return object.is_object() && object.contains(key) ? object[key] : json(nullptr);
}
std::string text(const json& object, const char* key) {
  const json v = member(object, key);
  return v.is_string() ? v.get<std::string>() : std::string();
}
json numberOrNull(const json& object, const char* key) {
  const json v = member(object, key);
  return v.is_number() ? v : json(nullptr);
}
json arrayOf(const json& object, const char* key) {
  const json v = member(object, key);
  return v.is_array() ? v : json::array();
}
json stringsOf(const json& object, const char* key) {
  json out = json::array();
  for (const json& v : arrayOf(object, key))
    if (v.is_string()) out.push_back(v);
  return out;
}

json fileLink(const std::string& relative) {
  return "/files/" + relative;
}

json linkOrNull(const json& entry, const char* key) {
  const json v = member(entry, key);
  return v.is_string() ? fileLink(v.get<std::string>()) : json(nullptr);
}

// An asset's JSON files, each read through the checked reader; the first
// problem found is the asset's (it is shown as unreadable, the others as usual).
struct AssetFiles {
  json asset, manifest, stats;
  std::string problem;
};

AssetFiles readAssetFiles(const fs::path& dir, const std::string& name, bool with_stats) {
  AssetFiles files;
  const auto read = [&](const char* file, json& into) {
    LibraryJson j = readLibraryJson(dir, name + "/" + file, kMaxAssetJsonBytes);
    if (!j.problem.empty() && files.problem.empty()) files.problem = j.problem;
    into = j.value.is_object() ? j.value : json(nullptr);
    if (j.present && j.problem.empty() && !j.value.is_object() && files.problem.empty())
      files.problem = (dir / name / file).string() + " is not a JSON object";
  };
  read("asset.json", files.asset);
  read("manifest.json", files.manifest);
  if (with_stats) read("stats.json", files.stats);
  return files;
}

json verdictOf(const json& verdicts, const std::string& name, const std::string& input_hash) {
  const json v = member(verdicts, name.c_str());
  if (!v.is_object() || !isVerdictStatus(text(v, "status"))) return nullptr;
  return {{"status", text(v, "status")},
          {"note", text(v, "note")},
          {"updated", text(v, "updated")},
          {"stale", text(v, "input_hash") != input_hash}};
}

json summary(const json& entry, const json& verdicts, const AssetFiles& files) {
  const std::string name = text(entry, "name");
  json s = {{"name", name}, {"status", text(entry, "status")}};
  s["message"] = member(entry, "message").is_string() ? member(entry, "message") : json(nullptr);
  const json job = member(entry, "job");
  s["preset"] = member(job, "preset");
  s["wedge"] = member(job, "wedge");
  const json seed = member(job, "seed");
  s["seed"] = !seed.is_null() ? seed : member(member(files.manifest, "inputs"), "seed");
  s["tags"] = stringsOf(files.asset, "tags");
  json lods = json::array();
  for (const json& lod : arrayOf(files.asset, "lods"))
    if (lod.is_object()) lods.push_back(lod);
  s["triangles"] = !lods.empty() ? numberOrNull(lods[0], "triangles") : json(nullptr);
  s["size_m"] = member(files.asset, "size_m").is_array() ? member(files.asset, "size_m") : json(nullptr);
  // LOD0's pixels per metre, with a texture set (docs/formats.md, asset.json's lods).
  s["texel_density"] = !lods.empty() ? numberOrNull(lods[0], "texel_density") : json(nullptr);
  s["bake_seconds"] = numberOrNull(member(member(files.manifest, "timings"), "stages"), "total");
  s["input_hash"] = text(entry, "input_hash");
  json links = {{"render", linkOrNull(entry, "render")},   {"movie", linkOrNull(entry, "movie")},
                {"asset", linkOrNull(entry, "asset")},     {"manifest", linkOrNull(entry, "manifest")},
                {"failure", linkOrNull(entry, "failure")}, {"lods", json::array()}};
  for (const json& lod : lods)
    if (member(lod, "file").is_string())
      links["lods"].push_back(
          {{"level", member(lod, "level").is_number_integer() ? member(lod, "level") : json(0)},
           {"file", fileLink(name + "/" + text(lod, "file"))},
           {"triangles", member(lod, "triangles").is_number() ? member(lod, "triangles") : json(0)}});
  s["files"] = links;
  s["review"] = verdictOf(verdicts, name, text(entry, "input_hash"));
  if (!files.problem.empty()) {
    // Listed with the failed jobs, with what is wrong, instead of failing the grid.
    s["status"] = "unreadable";
    s["message"] = files.problem + "; bake the asset again, or remove what is in its way";
  }
  return s;
}

bool isFinished(const json& entry) {
  const std::string status = text(entry, "status");
  return status == "ok" || status == "skipped-resumed";
}

// The asset's files when the index says it baked and its name is a folder of OUT.
AssetFiles filesOf(const fs::path& dir, const json& entry, bool with_stats) {
  const std::string name = text(entry, "name");
  if (!isAssetName(name)) {
    AssetFiles refused;
    refused.problem =
        (dir / "index.json").string() + " names an asset '" + name + "', which is not a folder name of the library";
    return refused;
  }
  return isFinished(entry) ? readAssetFiles(dir, name, with_stats) : AssetFiles{};
}

}  // namespace

json libraryIndexAssets(const fs::path& dir) {
  const fs::path file = dir / "index.json";
  const std::string rewrite = "write it again with `rockbake library --index-only " + dir.string() + "`";
  const LibraryJson index = readLibraryJson(dir, "index.json", kMaxLibraryJsonBytes);
  if (!index.present)
    throw InputError({file.string()}, "", "not found: review serves a baked library",
                     "bake one first with `rockbake library LIBRARY.yaml -o " + dir.string() + "`");
  if (!index.problem.empty()) throw InputError({file.string()}, "", index.problem, "move it away and " + rewrite);
  if (!member(index.value, "assets").is_array())
    throw InputError({file.string()}, "", "is not a library index (no \"assets\" list)", rewrite);
  return index.value["assets"];
}

json assetSummaries(const fs::path& dir, const json& verdicts) {
  json out = json::array();
  for (const json& entry : libraryIndexAssets(dir)) {
    if (!member(entry, "name").is_string()) continue;
    out.push_back(summary(entry, verdicts, filesOf(dir, entry, false)));
  }
  return out;
}

std::optional<json> assetDetail(const fs::path& dir, const std::string& name, const json& verdicts) {
  for (const json& entry : libraryIndexAssets(dir)) {
    if (!member(entry, "name").is_string() || text(entry, "name") != name) continue;
    const AssetFiles files = filesOf(dir, entry, true);
    json d = summary(entry, verdicts, files);
    d["asset"] = files.asset;
    d["lods"] = arrayOf(files.asset, "lods");
    d["stages"] = member(files.stats, "stages");
    d["bake_preset"] = member(files.stats, "preset");
    d["job"] = member(entry, "job");
    return d;
  }
  return std::nullopt;
}

}  // namespace rockbake
