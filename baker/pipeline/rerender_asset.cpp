#include "pipeline/rerender_asset.h"

#include <fstream>

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
  RenderOutputs out = rerenderAsset(request);
  updateManifestOutputs(before, options.template_name.empty() ? request.params.template_name : options.template_name,
                        request.still_name);
  return out;
}

}  // namespace rockbake
