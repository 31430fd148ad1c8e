#include "pipeline/rerender_asset.h"

#include <fstream>
#include <stdexcept>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "core/sha256.h"
#include "pipeline/asset_folder.h"
#include "pipeline/manifest.h"
#include "preset/yaml_text.h"

namespace rockbake {
namespace {

namespace fs = std::filesystem;

nlohmann::json readJson(const fs::path& file) {
  try {
    std::ifstream in(file);
    return nlohmann::json::parse(in);
  } catch (const std::exception& e) {
    throw InputError({file.string()}, "", std::string("unreadable: ") + e.what(), "bake the asset again");
  }
}

// The preset's fingerprint as the bake recorded it (manifest.json), so the
// new renders carry the same rockbake:preset_hash as the first ones.
std::string recordedFingerprint(const fs::path& dir, const nlohmann::json& resolved) {
  const fs::path manifest = dir / kManifestFile;
  if (fs::is_regular_file(manifest)) {
    const nlohmann::json m = readJson(manifest);
    if (m.contains("inputs") && m["inputs"].contains("preset_sha256"))
      return m["inputs"]["preset_sha256"].get<std::string>();
  }
  return sha256Hex(resolved.dump());
}

// The folder's hidden copy of what a re-render replaces, until it has succeeded.
constexpr const char* kPreviousRenders = ".rerender-previous";

// What a re-render writes into the folder, relative to it (render/render_asset.h).
std::vector<fs::path> rerenderOutputs(const RenderRequest& r) {
  const bool own = r.still_name == "render";
  std::vector<fs::path> files = {own ? "scene.pov" : r.still_name + ".pov", r.still_name + ".exr",
                                 r.still_name + ".png"};
  if (own && r.params.turntable_frames > 0)
    for (const char* f : {"turntable", "turntable_sheet.exr", "turntable_sheet.png", "turntable.mp4"})
      files.emplace_back(f);
  return files;
}

// Puts back what an interrupted re-render moved aside, over whatever it had written.
void restorePrevious(const fs::path& dir) {
  const fs::path previous = dir / kPreviousRenders;
  if (!fs::is_directory(fs::symlink_status(previous))) return;
  for (const auto& entry : fs::directory_iterator(previous)) {
    const fs::path target = dir / entry.path().filename();
    fs::remove_all(target);
    fs::rename(entry.path(), target);
  }
  fs::remove_all(previous);
}

// A re-render commits whole or not at all, as a bake does: what it replaces is moved aside
// first, and put back (over the new, partial outputs) when the render fails, so the folder and
// its manifest keep agreeing. A re-render killed midway is undone by the next one.
RenderOutputs renderOrRestore(const RenderRequest& request) {
  const fs::path& dir = request.asset_dir;
  const fs::path previous = dir / kPreviousRenders;
  // Only a folder of ours is restored from; a link or a file by that name (left or planted) is
  // removed, never followed: the renders must not be moved out of the asset.
  const fs::file_status status = fs::symlink_status(previous);
  if (fs::exists(status) && !fs::is_directory(status)) fs::remove(previous);
  restorePrevious(dir);
  if (!fs::create_directory(previous))
    throw std::runtime_error("cannot set the renders aside: " + previous.string() + " could not be made anew");
  const std::vector<fs::path> outputs = rerenderOutputs(request);
  bool rendering = false;
  try {
    for (const fs::path& f : outputs)
      if (fs::exists(fs::symlink_status(dir / f))) fs::rename(dir / f, previous / f.filename());
    rendering = true;
    RenderOutputs out = rerenderAsset(request);
    fs::remove_all(previous);
    return out;
  } catch (...) {
    // Before the render, every output is either set aside or was never there; after it started,
    // what stands at an output's name is the render's, partial, and goes.
    if (rendering)
      for (const fs::path& f : outputs) fs::remove_all(dir / f);
    restorePrevious(dir);
    throw;
  }
}

}  // namespace

RenderOutputs rerenderAssetFolder(const RerenderOptions& options) {
  const fs::path& dir = options.asset_dir;
  const fs::path stats_file = dir / "stats.json";
  if (!fs::is_regular_file(stats_file) || !fs::is_regular_file(dir / "rock_mesh.inc"))
    throw InputError({dir.string()}, "", "not a rendered asset folder (no stats.json or rock_mesh.inc)",
                     "bake it first with `rockbake bake PRESET` (without --no-mesh / --no-render)");
  const nlohmann::json stats = readJson(stats_file);
  RenderRequest request;
  try {
    const nlohmann::json& preset = stats.at("preset");
    const nlohmann::json& render = preset.at("render");
    request.asset_dir = dir;
    request.params.template_name = render.at("template").get<std::string>();
    request.params.width = render.at("width").get<int>();
    request.params.height = render.at("height").get<int>();
    request.params.quality = render.value("quality", request.params.quality);
    request.params.antialias = render.value("antialias", request.params.antialias);
    request.params.turntable_frames = render.at("turntable").value("frames", 0);
    request.params.turntable_fps = render.at("turntable").value("fps", request.params.turntable_fps);
    request.params.turntable_lookdev = render.at("turntable").value("lookdev", false);
    request.template_override = options.template_name;
    request.preset_name = preset.at("name").get<std::string>();
    request.seed = preset.at("seed").get<std::uint64_t>();
    request.preset_hash = recordedFingerprint(dir, preset);
  } catch (const nlohmann::json::exception& e) {
    throw InputError({stats_file.string()}, "preset", std::string("unreadable: ") + e.what(), "bake the asset again");
  }
  request.threads = options.threads;
  const std::string& own = request.params.template_name;
  request.still_name = !options.output.empty() ? options.output
                       : options.template_name.empty() || options.template_name == own
                           ? "render"
                           : "render_" + options.template_name;
  if (!isAssetName(request.still_name))  // the same rule as asset names: a-z, 0-9, _ and -
    throw InputError({"--output"}, "", "'" + request.still_name + "' is not a file name of a-z, 0-9, '_' and '-'",
                     "give a name such as render_debug");
  // A bake of the same asset (which would exchange the folder under the renders) waits for this one.
  fs::path asset = fs::absolute(dir).lexically_normal();
  if (asset.filename().empty()) asset = asset.parent_path();  // "out/goblin/"
  const AssetLock lock(asset);
  const AssetFolderSnapshot before = snapshotAssetFolder(dir);
  RenderOutputs out = renderOrRestore(request);
  updateManifestOutputs(before, options.template_name.empty() ? request.params.template_name : options.template_name,
                        request.still_name);
  return out;
}

}  // namespace rockbake
