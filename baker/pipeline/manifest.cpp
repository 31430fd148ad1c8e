#include "pipeline/manifest.h"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <variant>

#include <fmt/chrono.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/sha256.h"
#include "platform/atomic_file.h"
#include "preset/preset_json.h"

namespace rockbake {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using nlohmann::ordered_json;

fs::path normalBase(const fs::path& base_dir) {
  return fs::absolute(base_dir.empty() ? fs::path(".") : base_dir).lexically_normal();
}

fs::path presetBase(const Preset& preset, const ManifestInputs& inputs) {
  return normalBase(inputs.base_dir.empty() ? preset.file.parent_path() : inputs.base_dir);
}

std::string relativeTo(const fs::path& file, const fs::path& base) {
  if (file.empty()) return {};  // a preset made in memory has no file
  const fs::path relative = fs::absolute(file).lexically_normal().lexically_relative(base);
  return (relative.empty() ? file : relative).generic_string();
}

// The files a preset reads besides itself.
std::vector<fs::path> presetInputFiles(const Preset& preset) {
  if (const auto* image = std::get_if<ImageShape>(&preset.shape.kind)) return {image->path};
  if (const auto* mesh = std::get_if<MeshShape>(&preset.shape.kind)) return {mesh->path};
  return {};
}

// presetToJson with the input files' paths made relative to `base`.
json portablePreset(const Preset& preset, const fs::path& base) {
  json resolved = presetToJson(preset);
  for (const char* kind : {"image", "mesh"})
    if (resolved.contains("shape") && resolved["shape"].contains(kind) && resolved["shape"][kind].contains("path"))
      resolved["shape"][kind]["path"] = relativeTo(resolved["shape"][kind]["path"].get<std::string>(), base);
  return resolved;
}

json inputFilesJson(const Preset& preset, const fs::path& base) {
  json files = json::array();
  for (const auto& file : presetInputFiles(preset))
    files.push_back({{"path", relativeTo(file, base)}, {"sha256", sha256File(file)}});
  return files;
}

std::string utcNow() {
  return fmt::format("{:%Y-%m-%dT%H:%M:%SZ}",
                     fmt::gmtime(std::chrono::system_clock::to_time_t(std::chrono::system_clock::now())));
}

bool isBookkeeping(const fs::path& relative) {
  if (relative.empty() || relative == kManifestFile || relative == kFailureFile) return true;
  for (const auto& part : relative)
    if (!part.empty() && part.string().front() == '.') return true;  // atomic-write temporaries
  return false;
}

std::map<std::string, AssetFolderSnapshot::Stamp> scanFolder(const fs::path& dir) {
  std::map<std::string, AssetFolderSnapshot::Stamp> files;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return files;
  for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::recursive_directory_iterator();
       it.increment(ec)) {
    const fs::path relative = it->path().lexically_relative(dir);
    if (isBookkeeping(relative)) {
      if (it->is_directory()) it.disable_recursion_pending();
      continue;
    }
    struct stat st {};
    if (!it->is_regular_file() || ::stat(it->path().c_str(), &st) != 0) continue;
    files[relative.generic_string()] = {std::uint64_t(st.st_ino),
                                        std::int64_t(st.st_mtim.tv_sec) * 1000000000 + st.st_mtim.tv_nsec,
                                        std::uintmax_t(st.st_size)};
  }
  return files;
}

// The folder's files written since `before` (new, or replaced: atomic writes give a new inode and time
// stamp), as manifest outputs {path, size, sha256} by path. Files left from earlier are not among them.
std::map<std::string, ordered_json> writtenSince(const AssetFolderSnapshot& before) {
  std::map<std::string, ordered_json> written;
  for (const auto& [path, stamp] : scanFolder(before.dir)) {
    const auto old = before.files.find(path);
    if (old != before.files.end() && old->second.inode == stamp.inode && old->second.mtime_ns == stamp.mtime_ns &&
        old->second.size == stamp.size)
      continue;
    written[path] = {{"path", path}, {"size", stamp.size}, {"sha256", sha256File(before.dir / path)}};
  }
  return written;
}

}  // namespace

std::string hostName() {
  char name[256] = {};
  if (::gethostname(name, sizeof name - 1) != 0) return "unknown";
  return name;
}

json jobToJson(const std::string& asset_name, const ManifestInputs& inputs) {
  json wedge_set = json::array();
  for (const auto& s : inputs.wedge_sets) wedge_set.push_back(s);
  return {{"name", asset_name},
          {"preset", inputs.preset_file},
          {"wedge", inputs.wedge.empty() ? json(nullptr) : json(inputs.wedge)},
          {"wedge_set", wedge_set},
          {"set", inputs.overrides.sets},
          {"seed", inputs.overrides.seed ? json(*inputs.overrides.seed) : json(nullptr)},
          {"resolution", inputs.overrides.resolution ? json(*inputs.overrides.resolution) : json(nullptr)}};
}

json libraryToJson(const ManifestInputs& inputs) {
  if (inputs.library_file.empty()) return nullptr;
  return {{"file", inputs.library_file}, {"sha256", inputs.library_sha256}};
}

std::string bakeInputHash(const Preset& preset, const BakeStages& given, const fs::path& base_dir) {
  const fs::path base = normalBase(base_dir);
  const BakeStages stages = given.applied();
  const json fingerprint = {{"preset", portablePreset(preset, base)},
                            {"options", {{"mesh", stages.mesh}, {"render", stages.render}}},
                            {"baker_version", ROCKBAKE_VERSION},
                            {"input_files", inputFilesJson(preset, base)}};
  return sha256Hex(fingerprint.dump());
}

std::string presetFingerprint(const Preset& preset, const ManifestInputs& inputs) {
  return sha256Hex(portablePreset(preset, presetBase(preset, inputs)).dump());
}

AssetFolderSnapshot beginAssetFolder(const fs::path& asset_dir) {
  // The manifest goes first: from here on the folder does not look finished.
  fs::remove(asset_dir / kManifestFile);
  fs::remove(asset_dir / kFailureFile);
  return {asset_dir, scanFolder(asset_dir)};
}

AssetFolderSnapshot snapshotAssetFolder(const fs::path& asset_dir) {
  return {asset_dir, scanFolder(asset_dir)};
}

void updateManifestOutputs(const AssetFolderSnapshot& before, const std::string& template_name,
                           const std::string& still_name) {
  const fs::path file = before.dir / kManifestFile;
  if (!fs::is_regular_file(file)) return;
  ordered_json manifest;
  {
    std::ifstream in(file);
    manifest = ordered_json::parse(in);
  }
  std::map<std::string, ordered_json> outputs;
  for (auto& output : manifest.at("outputs")) outputs[output.at("path").get<std::string>()] = output;
  for (auto& [path, output] : writtenSince(before)) outputs[path] = std::move(output);
  manifest["outputs"] = ordered_json::array();
  for (auto& [path, output] : outputs) manifest["outputs"].push_back(std::move(output));
  manifest["rerender"] = {{"template", template_name}, {"still", still_name}};
  manifest["timings"]["rerendered_at"] = utcNow();
  writeFileAtomically(file, manifest.dump(2) + "\n");
}

void writeManifest(const AssetFolderSnapshot& before, const Preset& preset, const ManifestInputs& given,
                   const BakeStages& given_stages, const ManifestStats& stats, const ordered_json& timings) {
  const BakeStages stages = given_stages.applied();
  ManifestInputs inputs = given;
  const fs::path base = presetBase(preset, inputs);
  if (inputs.preset_file.empty()) inputs.preset_file = relativeTo(preset.file, base);

  ordered_json outputs = ordered_json::array();
  for (auto& [path, output] : writtenSince(before)) outputs.push_back(std::move(output));

  const json resolved = portablePreset(preset, base);
  ordered_json manifest;
  manifest["rockbake_manifest"] = 1;
  manifest["asset"] = preset.name;
  manifest["inputs"] = {{"input_hash", bakeInputHash(preset, stages, base)},
                        {"baker_version", ROCKBAKE_VERSION},
                        {"preset_sha256", presetFingerprint(preset, inputs)},
                        {"seed", preset.seed},
                        {"options", {{"mesh", stages.mesh}, {"render", stages.render}}},
                        {"job", jobToJson(preset.name, inputs)},
                        {"library", libraryToJson(inputs)},
                        {"input_files", inputFilesJson(preset, base)},
                        {"preset", resolved}};
  manifest["outputs"] = outputs;
  manifest["stats"] = {{"cycles", stats.cycles},
                       {"rock_voxels_initial", stats.rock_voxels_initial},
                       {"rock_voxels_final", stats.rock_voxels_final},
                       {"colluvium_voxels", stats.colluvium_voxels}};
  ordered_json run = timings;
  run["finished_at"] = utcNow();
  manifest["timings"] = run;
  manifest["host"] = hostName();
  writeFileAtomically(before.dir / kManifestFile, manifest.dump(2) + "\n");
}

bool isCompleteAsset(const fs::path& asset_dir, const std::string& input_hash) {
  try {
    std::ifstream in(asset_dir / kManifestFile);
    if (!in) return false;
    const json manifest = json::parse(in);
    if (manifest.at("inputs").at("input_hash").get<std::string>() != input_hash) return false;
    for (const auto& output : manifest.at("outputs")) {
      std::error_code ec;
      const fs::path file = asset_dir / output.at("path").get<std::string>();
      if (fs::file_size(file, ec) != output.at("size").get<std::uintmax_t>() || ec) return false;
    }
    return true;
  } catch (const std::exception&) {
    return false;  // unreadable or from another format: bake again
  }
}

void writeFailureRecord(const fs::path& asset_dir, const std::string& asset_name, const ManifestInputs& inputs,
                        const std::string& message, double seconds) {
  ordered_json record;
  record["asset"] = asset_name;
  record["status"] = "failed";
  record["message"] = message;
  record["inputs"] = {{"job", jobToJson(asset_name, inputs)}, {"library", libraryToJson(inputs)}};
  record["timings"] = {{"seconds", seconds}, {"finished_at", utcNow()}};
  record["host"] = hostName();
  writeFileAtomically(asset_dir / kFailureFile, record.dump(2) + "\n");
}

}  // namespace rockbake
