// BakeAsset: the recipe. One validated preset in, one asset folder out, as a
// sequence of phases, each a function of the one before (bake_asset.cpp):
//   start the simulation (the initial rock, or a checkpoint's state)
//   ─▶ simulate (cycles, checkpoints) ─▶ meshes and collision hulls, side by
//   side (pipeline/bake_meshes.h, bake_collision.h) ─▶ the texture set ─▶
//   exports and rock.vdb (rock_sdf = the meshes' smoothed field; with
//   --no-mesh, the occupancy) ─▶ render (EXR + PNG preview, turntable) ─▶
//   describe (asset.json) ─▶ stats.json ─▶ manifest.json (last) ─▶ commit.
// The bake writes into a hidden folder beside OUT/<name> and commits it in
// one step, replacing the previous asset only when that is an asset folder
// rockbake wrote (pipeline/asset_folder.h): a bake that fails or is
// interrupted leaves the previous complete asset folder, or none. Throws
// InputError, before any work, when OUT/<name> is not rockbake's to replace,
// OUT is a file, or another live process is writing the asset.
#pragma once

#include <atomic>
#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>

#include "inputs/resolve_shape.h"
#include "pipeline/bake_phases.h"
#include "pipeline/bake_stages.h"
#include "pipeline/manifest.h"
#include "preset/preset.h"
#include "sim/checkpoint_format.h"

namespace rockbake {

class AssetLock;

struct BakeOptions {
  std::filesystem::path out_dir = "out";  // assets go to out_dir / preset.name
  BakeStages stages;
  int render_threads = 0;     // POV-Ray's threads; 0: all cores
  double load_seconds = 0.0;  // time the caller spent loading the preset
  ManifestInputs manifest;    // what manifest.json records beyond the preset
  // When set and it turns true, the bake stops at the next cycle or stage
  // boundary by throwing BakeCancelled, before writing manifest.json.
  const std::atomic<bool>* cancel = nullptr;
  // When set, told how far the bake is (0..1) and which stage runs, at every
  // cycle and stage boundary (the studio's bake-final progress bar).
  std::function<void(double fraction, const std::string& stage)> progress;
  // > 0: write OUT/<name>/checkpoints/<time>.rbk each time the simulation
  // passes a multiple of this time (pipeline/checkpoint.h).
  double checkpoint_every = 0.0;
  // When set, the simulation starts from this checkpoint's state instead of
  // the initial rock (`rockbake resume`); the preset must be on its grid.
  const Checkpoint* resume = nullptr;
  // The asset's lock when the caller holds it (a library job keeps it for its
  // failure record); nullptr: the bake takes it.
  const AssetLock* lock = nullptr;
};

// The preset as a bake with these options makes it: without its texture: block
// when the texture stage is off, so the input hash, the manifest and stats.json
// say what was baked. Checkpoints keep the preset itself, so that `resume`
// with or without --no-textures reads it back the same.
Preset presetAsBaked(const Preset& preset, const BakeOptions& options);

class BakeCancelled : public std::runtime_error {
 public:
  BakeCancelled() : std::runtime_error("cancelled") {}
};

struct BakeSummary {
  std::filesystem::path asset_dir;
  int cycles = 0;
  std::size_t initial_rock = 0;
  std::size_t final_rock = 0;
  double seconds = 0.0;  // the bake's own, without load_seconds
  PhaseTimes timings;    // stats.json's "stages" (pipeline/bake_phases.h)
};

// `shape` is readInputs(preset) (pipeline/read_inputs.h), read before the bake
// so that a caller can check every input of several presets first; the
// two-argument form reads it itself.
BakeSummary bakeAsset(const Preset& preset, const ResolvedShape& shape, const BakeOptions& options);
BakeSummary bakeAsset(const Preset& preset, const BakeOptions& options);

}  // namespace rockbake
