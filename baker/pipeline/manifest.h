// manifest.json: the last file a bake writes in its asset folder (docs/formats.md, docs/libraries.md).
// Its presence says the folder is complete; it records what went in, what
// came out and how long it took:
//
//   {"rockbake_manifest": 1, "asset": NAME,
//    "inputs": {"input_hash", "baker_version", "preset_sha256", "seed", "options": {mesh, render},
//               "job": {name, preset, wedge, wedge_set, set, seed, resolution},
//               "library": {file, sha256} | null, "input_files": [{path, sha256}], "preset": {resolved}},
//    "outputs": [{path, size, sha256}, ...],   // every file this bake wrote, sorted by path
//    "stats": {cycles, rock_voxels_initial, rock_voxels_final, colluvium_voxels},
//    "timings": {...}, "host": NAME}
//
// Everything that varies from run to run is under "timings" and "host": two
// bakes of the same inputs on two machines give manifests that are equal once
// those two keys are removed. (stats.json holds stage seconds, so its sha256
// in "outputs" differs between runs too.) Paths are relative to the asset
// folder (outputs) or to the library's or preset's folder (inputs), never
// absolute, so they do not depend on where the files live.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "pipeline/bake_stages.h"
#include "preset/load_preset.h"
#include "preset/preset.h"

namespace rockbake {

inline constexpr const char* kManifestFile = "manifest.json";
// A library job that failed leaves this instead: {"asset", "status": "failed", "message", "inputs": {"job",
// "library"}, "timings", "host"}.
inline constexpr const char* kFailureFile = "failure.json";

// What the caller knows about a bake beyond the preset. Every field may be
// left empty for a plain `rockbake bake`.
struct ManifestInputs {
  std::filesystem::path base_dir;       // input paths are recorded relative to it; empty: the preset file's folder
  std::string preset_file;              // the preset relative to base_dir; empty: the preset file's name
  PresetOverrides overrides;            // everything applied on top of the preset file, in order
  std::string wedge;                    // a library job's wedge; empty: none
  std::vector<std::string> wedge_sets;  // that wedge's own overrides (also in overrides.sets)
  std::string library_file;             // the library file's name; empty: not a library job
  std::string library_sha256;
};

// The job as the index and the manifest show it: {name, preset, wedge, wedge_set, set, seed, resolution}.
nlohmann::json jobToJson(const std::string& asset_name, const ManifestInputs& inputs);
// {file, sha256}, or null outside a library.
nlohmann::json libraryToJson(const ManifestInputs& inputs);

// The fingerprint of everything that decides a bake's outputs: the resolved
// preset (incl. seed and asset name; input paths relative to base_dir), the
// stages run (BakeStages, applied), the baker version and the bytes of the files the
// preset reads (shape images, blockouts). 64 hex digits (SHA-256).
std::string bakeInputHash(const Preset& preset, const BakeStages& stages, const std::filesystem::path& base_dir);

// The preset's one fingerprint: SHA-256 (64 hex digits) of the resolved preset
// with its input paths relative to the inputs' base folder (the preset file's
// folder by default), so it does not depend on where the checkout lives. The
// manifest records it as inputs.preset_sha256 and renders as rockbake:preset_hash.
std::string presetFingerprint(const Preset& preset, const ManifestInputs& inputs);

// What an asset folder held before a bake: lets the manifest list exactly the
// files the bake wrote (new ones, and ones replaced since: atomic writes give
// every written file a new inode and time stamp).
struct AssetFolderSnapshot {
  struct Stamp {
    std::uint64_t inode = 0;
    std::int64_t mtime_ns = 0;
    std::uintmax_t size = 0;
  };
  std::filesystem::path dir;
  std::map<std::string, Stamp> files;  // relative path → stamp
};

// Call before a bake writes anything: removes the folder's manifest.json and
// failure.json, so that an interrupted bake never leaves a folder that looks
// finished, and takes the snapshot.
AssetFolderSnapshot beginAssetFolder(const std::filesystem::path& asset_dir);

struct ManifestStats {
  int cycles = 0;
  std::size_t rock_voxels_initial = 0;
  std::size_t rock_voxels_final = 0;
  std::size_t colluvium_voxels = 0;
};

// Writes <dir>/manifest.json atomically; call it after every other file.
// `timings` goes under "timings" as is (stage seconds and the like).
void writeManifest(const AssetFolderSnapshot& before, const Preset& preset, const ManifestInputs& inputs,
                   const BakeStages& stages, const ManifestStats& stats, const nlohmann::ordered_json& timings);

// What the folder holds now, manifest untouched (for updateManifestOutputs).
AssetFolderSnapshot snapshotAssetFolder(const std::filesystem::path& asset_dir);

// After `rockbake render` wrote renders into a finished folder: the manifest's
// outputs get the new sizes and hashes of the files written since `before`
// (new files are added), and "rerender" records the template, so the manifest
// keeps describing the folder and a library re-run still finds it complete.
// A folder without a manifest is left without one.
void updateManifestOutputs(const AssetFolderSnapshot& before, const std::string& template_name,
                           const std::string& still_name = "render");

// True when asset_dir holds a manifest.json that parses, whose input hash is
// `input_hash`, and whose every listed output exists with its listed size.
bool isCompleteAsset(const std::filesystem::path& asset_dir, const std::string& input_hash);

// Records a library job's failure in <asset_dir>/failure.json (atomically).
void writeFailureRecord(const std::filesystem::path& asset_dir, const std::string& asset_name,
                        const ManifestInputs& inputs, const std::string& message, double seconds);

// The host name (for "host").
std::string hostName();

}  // namespace rockbake
