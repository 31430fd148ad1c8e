// A library's index.json and contact_sheet.png (docs/libraries.md), built from the asset
// folders on disk, so that shards baked on several machines into one OUT (or
// copied together) give the same index as one machine baking everything.
//
// index.json:
//   {"rockbake_index": 1, "baker_version",
//    "libraries": [{file, sha256}, ...],              // distinct, sorted
//    "assets": [                                      // by name, numbers in natural order (s9 < s10)
//      {"name", "status": "ok" | "skipped-resumed" | "failed",
//       "job": {name, preset, wedge, wedge_set, set, seed, resolution},
//       "input_hash", "manifest": "<name>/manifest.json", "render": "<name>/render.png" | null,
//       "movie": "<name>/turntable.mp4" | null, "asset": "<name>/asset.json" | null}
//      {"name", "status": "failed", "message", "job", "failure": "<name>/failure.json"}
//      {"name", "status": "damaged", "message"}],     // manifest.json / failure.json there but unreadable
//    "counts": {"ok", "skipped-resumed", "failed", "damaged"},
//    "contact_sheet": "contact_sheet.png" | null,
//    "timings": {...}, "host"}
//
// An asset folder is one holding manifest.json (a finished bake) or
// failure.json (a library job that failed); folders with neither (a bake
// interrupted or still running) are left out. A folder whose manifest.json or
// failure.json is cut off or garbled is listed as "damaged", with a warning. "skipped-resumed" is what the
// run that writes the index did with an asset it found complete; otherwise a
// finished asset is "ok". "timings" and "host" are the only keys that vary
// between runs over the same folders.
#pragma once

#include <filesystem>
#include <map>
#include <string>

#include <nlohmann/json_fwd.hpp>

namespace rockbake {

inline constexpr const char* kIndexFile = "index.json";
inline constexpr const char* kContactSheetFile = "contact_sheet.png";

struct IndexCounts {
  int ok = 0;
  int skipped_resumed = 0;
  int failed = 0;
  // Folders whose manifest.json or failure.json is there but cannot be read (cut off, garbled): listed
  // with status "damaged" and a warning; bake them again.
  int damaged = 0;
};

// Writes OUT/index.json and OUT/contact_sheet.png (when there is at least one
// asset) atomically. When the sheet cannot be made (no font), the index is
// still written, with "contact_sheet": null, and the error is thrown after. `run_status` maps asset names to
// "skipped-resumed" for the assets this run found complete; `timings` goes under "timings".
IndexCounts writeLibraryIndex(const std::filesystem::path& out_dir,
                              const std::map<std::string, std::string>& run_status,
                              const nlohmann::ordered_json& timings);

}  // namespace rockbake
