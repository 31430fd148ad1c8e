// The baked assets `rockbake blender-library` delivers (docs/libraries.md, "Blender's asset
// browser"), found in what the command line names: asset folders (`rockbake bake` writes
// OUT/<name>/: manifest.json, asset.json, rock.glb, ...) and library folders (`rockbake library`
// writes OUT/index.json beside the asset folders; a folder of plain bakes has the asset folders
// alone).
//
// An asset folder named on its own must be a finished bake with meshes and a GLB: anything less
// is an InputError. In a library folder the asset folders that cannot be delivered (a failed job,
// a bake without meshes or without `glb` in its export) are skipped, each with a sentence saying
// why; a library with none left is an InputError.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace rockbake {

struct BakedAsset {
  std::string name;           // asset.json's name: the .blend's and the object's
  std::filesystem::path dir;  // the asset folder, absolute
  nlohmann::json asset;       // asset.json, checked: name, size_m, lods (files inside dir), ...
  nlohmann::json inputs;      // manifest.json's "inputs" (the job, the library, the seed)
  std::string catalog;        // its catalogue path (delivery/blender_catalogs.h)
  std::string preview;        // asset.json's preview when the file is there; empty: none
};

struct BakedAssets {
  std::vector<BakedAsset> assets;    // in the order of the sources, a library's by folder name
  std::vector<std::string> skipped;  // one sentence per asset folder of a library left out
};

// Throws InputError (exit status 2) for a source that does not exist, is not a folder, or is neither
// an asset folder nor a library folder; for an asset folder that cannot be delivered; for a library
// folder with nothing to deliver; and for two assets of one name.
BakedAssets findBakedAssets(const std::vector<std::filesystem::path>& sources);

}  // namespace rockbake
