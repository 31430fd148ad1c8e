// BakeAsset: the recipe. One validated preset in, one asset folder out:
//   preset ─▶ initial rock ─▶ weathering cycles ─▶ meshes and exports
//   (pipeline/bake_meshes.h) ─▶ rock.vdb (rock_sdf = the meshes' smoothed
//   field) ─▶ POV-Ray render (EXR + PNG preview) ─▶ stats.json ─▶
//   manifest.json (last), all in OUT/<name>/; with --no-mesh, rock.vdb
//   (occupancy rock_sdf), stats.json and manifest.json
// Each stage is a function of the previous stage's value; every file is
// written atomically, so a failed bake never leaves a file that looks complete.
#pragma once

#include <atomic>
#include <filesystem>
#include <stdexcept>

#include "inputs/resolve_shape.h"
#include "pipeline/manifest.h"
#include "preset/preset.h"

namespace rockbake {

struct BakeOptions {
  std::filesystem::path out_dir = "out";  // assets go to out_dir / preset.name
  bool mesh = true;                       // --no-mesh turns the mesh stage off
  bool render = true;                     // --no-render turns the render stage off (needs mesh)
  int render_threads = 0;                 // POV-Ray's threads; 0: all cores
  double load_seconds = 0.0;              // time the caller spent loading the preset
  ManifestInputs manifest;                // what manifest.json records beyond the preset
  // When set and it turns true, the bake stops at the next cycle or stage
  // boundary by throwing BakeCancelled, before writing manifest.json.
  const std::atomic<bool>* cancel = nullptr;
};

class BakeCancelled : public std::runtime_error {
 public:
  BakeCancelled() : std::runtime_error("cancelled") {}
};

struct BakeSummary {
  std::filesystem::path asset_dir;
  int cycles = 0;
  std::size_t initial_rock = 0;
  std::size_t final_rock = 0;
  double seconds = 0.0;
};

// `shape` is readInputs(preset) (pipeline/read_inputs.h), read before the bake
// so that a caller can check every input of several presets first; the
// two-argument form reads it itself.
BakeSummary bakeAsset(const Preset& preset, const ResolvedShape& shape, const BakeOptions& options);
BakeSummary bakeAsset(const Preset& preset, const BakeOptions& options);

}  // namespace rockbake
