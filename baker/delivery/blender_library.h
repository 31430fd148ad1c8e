// `rockbake blender-library SOURCE... -o OUT` (docs/libraries.md, "Blender's asset browser";
// docs/command-line.md): a folder Blender's Asset Browser reads as an asset library, made from
// baked assets with Blender itself, run as its own process (delivery/blender_program.h) on the
// script the data folder ships (blender/blender_library.py, from scripts/blender/):
//
//   OUT/<asset>.blend                  one per asset: the LOD0 object, marked as an asset with its
//                                      catalogue, description, tags and preview, its maps packed;
//                                      the further LODs and the collision hulls beside it in
//                                      collections excluded from the view layer
//   OUT/blender_assets.cats.txt        the catalogues (delivery/blender_catalogs.h)
//   OUT/rockbake_blender_library.json  what was written from where: says the folder is rockbake's
//
// Everything is checked before anything is written: the sources (delivery/baked_assets.h), Blender,
// the script, and OUT, which must be absent, an empty folder or a library rockbake wrote (the
// marker file): anything else is refused. Every file is written atomically (a hidden temporary in
// OUT renamed over the target), so a run that fails or is killed leaves each file old or new,
// never cut off; a re-run replaces the library: the .blend files of assets no longer given are
// removed, and leftovers of a killed run with them.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "delivery/baked_assets.h"
#include "delivery/blender_catalogs.h"

namespace rockbake {

inline constexpr const char* kBlenderLibraryMarker = "rockbake_blender_library.json";
inline constexpr const char* kBlenderLibraryScript = "blender/blender_library.py";  // in the data folder

struct BlenderLibraryOptions {
  std::vector<std::filesystem::path> sources;  // asset folders and library folders
  std::filesystem::path out_dir;
  std::string blender;  // --blender PATH; empty: $ROCKBAKE_BLENDER, else blender on PATH
  int jobs = 1;         // Blender processes at once
  int threads = 0;      // cores shared among them; 0: all
};

struct BlenderLibraryResult {
  std::size_t written = 0;  // .blend files written
  std::size_t failed = 0;   // assets Blender failed on (their message logged; an older .blend stays)
  std::size_t skipped = 0;  // asset folders of a library left out (logged)
  std::size_t removed = 0;  // .blend files of an earlier run whose assets were not given again
};

// What OUT holds now: nothing yet (absent or empty), or a library rockbake wrote, with the .blend
// files its marker lists. Throws InputError when OUT is a file, or a folder holding other things.
struct LibraryFolder {
  bool ours = false;
  std::vector<std::string> previous_files;
};
LibraryFolder checkLibraryFolder(const std::filesystem::path& out_dir);

// The asset's description in the Asset Browser: what it is, from which preset and seed, its size in
// metres and what else its .blend holds.
std::string assetDescription(const BakedAsset& asset);

// The job the script gets for one asset (its one argument, as JSON).
nlohmann::json blenderJob(const BakedAsset& asset, const BlenderCatalog& catalog, const std::filesystem::path& output);

// Checks, then writes the library. Exit-status-wise: InputError before anything is written; the
// result counts what Blender failed on.
BlenderLibraryResult writeBlenderLibrary(const BlenderLibraryOptions& options);

}  // namespace rockbake
