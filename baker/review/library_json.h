// A JSON file of a baked library (index.json, review.json, an asset's
// asset.json, manifest.json, stats.json) read as the /files/ route reads
// (docs/review.md, "The server's promises"): only a regular file strictly
// inside OUT (no link out of it, no FIFO, device or folder), opened without
// blocking, at most `max_bytes` long. Anyone may have put a file in OUT, so a
// bad one is reported, never waited on or read without end.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

namespace rockbake {

inline constexpr std::uint64_t kMaxLibraryJsonBytes = std::uint64_t(16) << 20;  // index.json, review.json
inline constexpr std::uint64_t kMaxAssetJsonBytes = std::uint64_t(4) << 20;     // an asset's own

struct LibraryJson {
  bool present = false;   // false: there is no such file (value is null, problem empty)
  nlohmann::json value;   // the parsed file, or null
  std::string problem;    // why it was not read: names the file and what is wrong
  bool not_json = false;  // read whole, but not JSON
};

// `relative` (a path under `library_dir`) read and parsed, or why not.
LibraryJson readLibraryJson(const std::filesystem::path& library_dir, const std::string& relative,
                            std::uint64_t max_bytes);

}  // namespace rockbake
