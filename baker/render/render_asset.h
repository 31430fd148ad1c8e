// The render stage takes AssetMeshes and RenderParams and gives renders
// (docs/rendering.md): scene → POV-Ray → EXR with metadata → OCIO PNG
// preview; optionally a turntable, its contact sheet and its movie.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "core/surface_mesh.h"
#include "preset/preset.h"
#include "render/scene.h"

namespace rockbake {

struct RenderRequest {
  std::filesystem::path asset_dir;     // OUT/<name>/; everything is written here
  RenderParams params;                 // the preset's render: block
  std::filesystem::path template_dir;  // empty: defaultRenderTemplatesDir()
  std::string template_override;       // `--template NAME`; empty: params.template_name
  // The still's files: <still_name>.exr and .png (and its scene, scene.pov for "render", else
  // <still_name>.pov). Only the bake's own still, "render", brings the turntable with it.
  std::string still_name = "render";
  std::filesystem::path ocio_config;  // empty: <template_dir>/ocio/config.ocio
  std::string preset_name;
  std::uint64_t seed = 0;
  std::string preset_hash;
  int threads = 0;  // POV-Ray's +WT; 0: all hardware threads (call it when the baker's own pool is idle)
  std::chrono::seconds timeout{1800};         // per POV-Ray run
  const std::atomic<bool>* cancel = nullptr;  // see PovrayJob::cancel
  // The texture set's LOD0 maps (render/scene.h): the meshes are then the textured LOD0 (with
  // uvs) and the templates that ask for them render them; empty: vertex colours only.
  RenderMaps maps;
  const ClastSet* clasts = nullptr;  // the stones on the apron (render/scene.h), or none
};

struct RenderOutputs {
  std::filesystem::path scene;                          // scene.pov
  std::filesystem::path mesh_include;                   // rock_mesh.inc
  std::filesystem::path render_exr;                     // render.exr
  std::filesystem::path render_png;                     // render.png
  std::vector<std::filesystem::path> turntable_frames;  // turntable/0000.exr, …
  std::filesystem::path turntable_sheet_exr;            // empty without a turntable
  std::filesystem::path turntable_sheet_png;
  std::filesystem::path turntable_movie;  // turntable.mp4; empty without a turntable
  double seconds_scene = 0;               // writing the include and scenes
  double seconds_still = 0;               // POV-Ray, the still
  double seconds_turntable = 0;           // POV-Ray, all frames
  double seconds_post = 0;                // metadata, contact sheet, PNG previews
  double seconds_movie = 0;               // turntable.mp4 (FFmpeg)
  double seconds_total = 0;
};

// Throws PovrayError (POV-Ray missing / failed / timed out), MovieError (FFmpeg
// missing or failed, render/turntable_movie.h) or
// std::runtime_error (template missing or with an unknown placeholder, I/O).
RenderOutputs renderAsset(const AssetMeshes& meshes, const RenderRequest& request);

// `rockbake render ASSET_DIR`: renders again from the asset folder's existing
// rock_mesh.inc (written by renderAsset; it records the framing), so neither
// the simulation nor the meshes are needed. Same outputs as renderAsset.
RenderOutputs rerenderAsset(const RenderRequest& request);

// Checks that POV-Ray (and FFmpeg, for a turntable movie) can be found on PATH
// before any work starts, so that a missing one is said in the first second,
// not after the simulation (docs/rendering.md, "Helper programs"). Throws
// PovrayError or MovieError with the messages running them would give.
void requireHelperPrograms(bool turntable_movie);

}  // namespace rockbake
