#include "render/render_asset.h"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <system_error>
#include <thread>

#include "render/exr_metadata.h"
#include "render/povray.h"
#include "render/preview.h"
#include "render/scene.h"
#include "render/turntable_movie.h"

#ifndef ROCKBAKE_VERSION
#define ROCKBAKE_VERSION "unknown"
#endif

namespace rockbake {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

std::string frameName(int i) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "%04d", i);
  return buf;
}

RenderMetadata metadataFor(const RenderRequest& r, int frame, const CameraSetup& cam) {
  RenderMetadata m;
  m.preset = r.preset_name;
  m.seed = std::to_string(r.seed);
  m.preset_hash = r.preset_hash;
  m.version = ROCKBAKE_VERSION;
  m.frame = frame;
  m.camera_location = cam.location;
  m.camera_look_at = cam.look_at;
  m.camera_angle = cam.angle_deg;
  return m;
}

// Rows [first, end) of each band a still is rendered in: `bands` runs of whole POV-Ray blocks
// (kPovrayBlockRows), as even as the blocks allow; fewer when the image has fewer blocks.
std::vector<std::pair<int, int>> stillBands(int height, int bands) {
  const int blocks = (height + kPovrayBlockRows - 1) / kPovrayBlockRows;
  const int n = std::clamp(bands, 1, std::max(1, blocks));
  std::vector<std::pair<int, int>> rows;
  for (int k = 0; k < n; ++k) {
    const int first = blocks * k / n * kPovrayBlockRows, end = blocks * (k + 1) / n * kPovrayBlockRows;
    rows.emplace_back(first, std::min(end, height));
  }
  return rows;
}

// POV-Ray writes to hidden temporaries; the final EXR (with metadata) appears atomically, so
// a killed render never leaves a file that looks finished. With `bands` above one, each band
// of rows is its own single-threaded POV-Ray process, run side by side and joined: a band cut
// at block boundaries has exactly the pixels of the whole render (docs/rendering.md), so the
// EXR's bytes do not depend on how many bands there were.
void renderOne(const RenderRequest& r, int bands, const std::filesystem::path& scene_rel,
               const std::filesystem::path& exr_rel, const RenderMetadata& md, int width, int height) {
  const std::vector<std::pair<int, int>> rows = stillBands(height, bands);
  std::vector<ExrBand> parts;
  for (std::size_t k = 0; k < rows.size(); ++k) {
    std::string tmp_name = ".";
    tmp_name += exr_rel.stem().string();
    if (rows.size() > 1) tmp_name += ".band" + std::to_string(k);
    tmp_name += ".povray.exr";
    parts.push_back({exr_rel.parent_path() / tmp_name, rows[k].first, rows[k].second});
  }
  const auto removeParts = [&] {
    std::error_code ec;
    for (const ExrBand& part : parts) std::filesystem::remove(r.asset_dir / part.file, ec);
  };
  const auto renderPart = [&](const ExrBand& part) {
    PovrayJob job;
    job.working_dir = r.asset_dir;
    job.scene = scene_rel;
    job.output = part.file;
    job.width = width;
    job.height = height;
    if (parts.size() > 1) job.first_row = part.first_row, job.end_row = part.end_row;
    job.quality = r.params.quality;
    job.antialias = r.params.antialias;
    job.threads = 1;
    job.timeout = r.timeout;
    job.cancel = r.cancel;
    runPovray(job);
  };
  try {
    if (parts.size() == 1) {
      renderPart(parts.front());
      writeExrWithMetadata(r.asset_dir / parts.front().file, r.asset_dir / exr_rel, md);
    } else {
      tbb::task_arena arena(int(parts.size()));
      arena.execute(
          [&] { tbb::parallel_for(std::size_t(0), parts.size(), [&](std::size_t k) { renderPart(parts[k]); }); });
      std::vector<ExrBand> files = parts;
      for (ExrBand& part : files) part.file = r.asset_dir / part.file;
      joinExrBands(files, r.asset_dir / exr_rel, md);
    }
  } catch (...) {
    removeParts();
    throw;
  }
  removeParts();
}

RenderOutputs renderScenes(const AssetMeshes* mesh_data, const RenderRequest& r) {
  const auto t0 = Clock::now();
  const auto template_dir = r.template_dir.empty() ? defaultRenderTemplatesDir() : r.template_dir;
  const auto ocio = r.ocio_config.empty() ? template_dir / "ocio" / "config.ocio" : r.ocio_config;
  const std::string name = r.template_override.empty() ? r.params.template_name : r.template_override;
  const int threads = r.threads > 0 ? r.threads : int(std::max(1u, std::thread::hardware_concurrency()));
  const int w = r.params.width, h = r.params.height;

  RenderOutputs out;
  const bool own_still = r.still_name == "render";
  const std::string scene_name = own_still ? "scene.pov" : r.still_name + ".pov";
  out.scene = r.asset_dir / scene_name;
  out.mesh_include = r.asset_dir / "rock_mesh.inc";
  out.render_exr = r.asset_dir / (r.still_name + ".exr");
  out.render_png = r.asset_dir / (r.still_name + ".png");

  const auto still_template = findTemplate(template_dir, name);
  std::filesystem::path turntable_template;
  if (r.params.turntable_frames > 0 && own_still) turntable_template = findTemplate(template_dir, "turntable");

  std::filesystem::create_directories(r.asset_dir);
  AssetFrame meshes;
  if (mesh_data) {
    writeMeshInclude(*mesh_data, out.mesh_include, r.maps, r.clasts);
    meshes = assetFrame(*mesh_data);
  } else {
    meshes = readAssetFrame(out.mesh_include);
  }
  const CameraSetup home = frameCamera(meshes, w, h);
  writeScene(still_template, scenePlaceholders(meshes, home, home, SceneFrame{}, "rock_mesh.inc", r.seed), out.scene);
  out.seconds_scene = since(t0);

  auto t = Clock::now();
  // One POV-Ray thread per image: with more, POV-Ray's adaptive antialiasing compares pixels
  // across blocks that other threads may or may not have rendered yet, so an image changes
  // from run to run on a loaded machine (docs/rendering.md). The still uses the cores as
  // bands of rows, one process each; turntable frames as frames side by side.
  renderOne(r, threads, scene_name, r.still_name + ".exr", metadataFor(r, 0, home), w, h);
  out.seconds_still = since(t);
  t = Clock::now();
  exrToPng(out.render_exr, out.render_png, ocio);
  out.seconds_post += since(t);

  const int frames = own_still ? r.params.turntable_frames : 0;
  if (frames > 0) {
    // The turntable frames render at the still's size; the contact sheet is
    // a grid of them.
    t = Clock::now();
    out.turntable_frames.resize(std::size_t(frames));
    tbb::task_arena arena(threads);
    arena.execute([&] {
      tbb::parallel_for(0, frames, [&](int i) {
        SceneFrame f{i, frames, 360.0 * i / frames, r.params.turntable_lookdev};
        const CameraSetup cam = frameCamera(meshes, w, h, f.turntable_deg);
        const std::filesystem::path scene_rel = std::filesystem::path("turntable") / (frameName(i) + ".pov");
        const std::filesystem::path exr_rel = std::filesystem::path("turntable") / (frameName(i) + ".exr");
        // The frame's scene lives beside its EXR but includes ../rock_mesh.inc
        // relative to the working directory (the asset folder).
        writeScene(turntable_template, scenePlaceholders(meshes, cam, home, f, "rock_mesh.inc", r.seed),
                   r.asset_dir / scene_rel);
        renderOne(r, 1, scene_rel, exr_rel, metadataFor(r, i, cam), w, h);
        out.turntable_frames[std::size_t(i)] = r.asset_dir / exr_rel;
      });
    });
    out.seconds_turntable = since(t);
    t = Clock::now();
    out.turntable_sheet_exr = r.asset_dir / "turntable_sheet.exr";
    out.turntable_sheet_png = r.asset_dir / "turntable_sheet.png";
    writeContactSheet(out.turntable_frames, out.turntable_sheet_exr, metadataFor(r, -1, home));
    exrToPng(out.turntable_sheet_exr, out.turntable_sheet_png, ocio);
    out.seconds_post += since(t);
    t = Clock::now();
    TurntableMovieJob movie;
    movie.frames = out.turntable_frames;
    movie.target = out.turntable_movie = r.asset_dir / "turntable.mp4";
    movie.fps = r.params.turntable_fps;
    movie.ocio_config = ocio;
    movie.cancel = r.cancel;
    writeTurntableMovie(movie);
    out.seconds_movie = since(t);
  }
  out.seconds_total = since(t0);
  return out;
}

}  // namespace

RenderOutputs renderAsset(const AssetMeshes& meshes, const RenderRequest& request) {
  return renderScenes(&meshes, request);
}

RenderOutputs rerenderAsset(const RenderRequest& request) {
  return renderScenes(nullptr, request);
}

namespace {

// True when `name` is an executable file in a folder of PATH (as execvp finds it).
bool onPath(const std::string& name) {
  if (name.find('/') != std::string::npos) return access(name.c_str(), X_OK) == 0;
  const char* path = std::getenv("PATH");
  std::string dirs = path ? path : "/usr/local/bin:/usr/bin:/bin";
  for (std::size_t start = 0; start <= dirs.size();) {
    std::size_t end = dirs.find(':', start);
    if (end == std::string::npos) end = dirs.size();
    const std::string dir = end > start ? dirs.substr(start, end - start) : ".";
    const std::filesystem::path candidate = std::filesystem::path(dir) / name;
    std::error_code ec;
    if (std::filesystem::is_regular_file(candidate, ec) && access(candidate.c_str(), X_OK) == 0) return true;
    start = end + 1;
  }
  return false;
}

}  // namespace

void requireHelperPrograms(bool turntable_movie) {
  const PovrayJob povray;
  if (!onPath(povray.executable))
    throw PovrayError("POV-Ray ('" + povray.executable +
                      "') was not found on PATH; rendering needs it: install it with: apt-get install povray "
                      "(Debian package 'povray'), or bake with --no-render");
  const TurntableMovieJob movie;
  if (turntable_movie && !onPath(movie.executable))
    throw MovieError("FFmpeg ('" + movie.executable +
                     "') was not found on PATH; turntable movies need it: install it with: apt-get install "
                     "ffmpeg (Debian package 'ffmpeg'), or set render.turntable.frames: 0");
}

}  // namespace rockbake
