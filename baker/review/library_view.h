// What the review page shows of a baked library (docs/review.md, "The JSON
// API"), read from OUT as it is on disk at each request: index.json's assets,
// each with what its asset.json, manifest.json and stats.json say, and its
// verdict from review.json (stale when the asset's input hash has changed
// since). File links are URLs under /files/, relative to OUT. Every file is
// read through review/library_json.h; an asset whose files cannot be read is
// listed as "unreadable" with what is wrong, and keys of the wrong type read
// as absent, so one bad asset never fails the list.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

namespace rockbake {

// OUT/index.json's "assets"; InputError naming the file and what to do when
// there is none, it cannot be read (review/library_json.h) or it is not an index.
nlohmann::json libraryIndexAssets(const std::filesystem::path& library_dir);

// One summary per asset, in the index's order: name, status ("unreadable" when
// its files cannot be read), message (failed jobs, unreadable assets), preset, wedge, seed, tags, triangles (LOD0),
// size_m, texel_density (LOD0) (null without texture maps), bake_seconds, input_hash, files {...}, review {status,
// note, updated, stale} or null. `verdicts` is review.json's "assets".
nlohmann::json assetSummaries(const std::filesystem::path& library_dir, const nlohmann::json& verdicts);

// The summary plus asset.json (`asset`), the per-LOD triangles (`lods`), the
// bake's stage times (`stages`), the library job (`job`) and the preset as the
// bake ran it (`bake_preset`, every default filled in). Nothing when the index has no such asset.
std::optional<nlohmann::json> assetDetail(const std::filesystem::path& library_dir, const std::string& name,
                                          const nlohmann::json& verdicts);

}  // namespace rockbake
