#include "delivery/baked_assets.h"

#include <algorithm>
#include <map>
#include <optional>

#include "core/error.h"
#include "delivery/blender_catalogs.h"
#include "platform/input_file.h"

namespace rockbake {

namespace fs = std::filesystem;

namespace {

constexpr std::uint64_t kMaxJsonBytes = std::uint64_t(16) << 20;

const char* const kWhatIsABake =
    "expected an asset folder (holding manifest.json, asset.json and rock.glb, as `rockbake bake -o OUT` writes "
    "OUT/<name>/) or a library folder (holding index.json or asset folders, as `rockbake library` writes)";

// A JSON object read from `file`, or why not.
std::optional<nlohmann::json> readJson(const fs::path& file, std::string& problem) {
  try {
    const InputFile in(file, "");
    if (in.size() > kMaxJsonBytes) {
      problem = file.filename().string() + " has " + std::to_string(in.size()) + " bytes, more than a bake writes";
      return std::nullopt;
    }
    nlohmann::json value = nlohmann::json::parse(in.read(0, in.size()), nullptr, false);
    if (value.is_discarded() || !value.is_object()) {
      problem = file.filename().string() + " is not a JSON object (cut off or garbled: bake it again)";
      return std::nullopt;
    }
    return value;
  } catch (const InputError& e) {
    problem = e.problem();
    return std::nullopt;
  }
}

bool isAssetName(const std::string& name) {
  return !name.empty() && name.size() <= 64 && std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || c == '-';
  });
}

// A file asset.json names: relative, inside the folder, a regular file there.
bool isFileInside(const fs::path& dir, const nlohmann::json& value) {
  if (!value.is_string()) return false;
  const fs::path relative(value.get<std::string>());
  if (relative.empty() || relative.is_absolute()) return false;
  for (const auto& part : relative)
    if (part == "..") return false;
  std::error_code ec;
  return fs::is_regular_file(fs::symlink_status(dir / relative, ec));
}

// Why asset.json cannot be delivered from `dir`, or nothing.
std::optional<std::string> assetJsonProblem(const fs::path& dir, const nlohmann::json& asset) {
  if (asset.value("rockbake_asset", 0) != 1) return "asset.json is not a rockbake asset description";
  if (!isAssetName(asset.value("name", std::string())))
    return "asset.json's name is not an asset name (1 to 64 of a-z 0-9 _ -)";
  const auto& size = asset.contains("size_m") ? asset["size_m"] : nlohmann::json();
  if (!size.is_array() || size.size() != 3 ||
      !std::all_of(size.begin(), size.end(), [](const auto& v) { return v.is_number(); }))
    return "asset.json has no size_m";
  const auto& lods = asset.contains("lods") ? asset["lods"] : nlohmann::json();
  if (!lods.is_array() || lods.empty() || !lods[0].is_object())
    return "asset.json lists no LOD: it was baked without meshes";
  for (const auto& lod : lods)
    if (!lod.is_object() || !isFileInside(dir, lod.value("file", nlohmann::json())))
      return "has no " + (lod.is_object() ? lod.value("file", std::string("LOD file")) : std::string("LOD file")) +
             ": its preset's export does not list glb (add glb to export: and bake again)";
  const auto& collision = asset.contains("collision") ? asset["collision"] : nlohmann::json();
  if (collision.is_object() && !isFileInside(dir, collision.value("file", nlohmann::json())))
    return "asset.json names collision.glb, which is not there";
  return std::nullopt;
}

// The asset in `dir`, or why it cannot be delivered.
std::optional<BakedAsset> loadAssetFolder(const fs::path& dir, std::string& problem) {
  std::error_code ec;
  if (!fs::is_regular_file(dir / "manifest.json", ec)) {
    problem = fs::is_regular_file(dir / "failure.json", ec) ? "a library job that failed (failure.json)"
                                                            : "holds no manifest.json: not a finished bake";
    return std::nullopt;
  }
  const auto manifest = readJson(dir / "manifest.json", problem);
  if (!manifest) return std::nullopt;
  if (manifest->value("rockbake_manifest", 0) != 1 || !(*manifest)["inputs"].is_object()) {
    problem = "manifest.json is not a rockbake manifest";
    return std::nullopt;
  }
  if (!fs::is_regular_file(dir / "asset.json", ec)) {
    problem = "holds no asset.json: it was baked without meshes (--no-mesh)";
    return std::nullopt;
  }
  auto asset = readJson(dir / "asset.json", problem);
  if (!asset) return std::nullopt;
  if (const auto why = assetJsonProblem(dir, *asset)) {
    problem = *why;
    return std::nullopt;
  }
  BakedAsset found;
  found.name = (*asset)["name"].get<std::string>();
  found.dir = fs::absolute(dir).lexically_normal();
  found.inputs = (*manifest)["inputs"];
  found.catalog = catalogPathForJob(found.inputs);
  if (isFileInside(dir, asset->value("preview", nlohmann::json())))
    found.preview = (*asset)["preview"].get<std::string>();
  found.asset = std::move(*asset);
  return found;
}

bool holdsAssetFolders(const fs::path& dir) {
  std::error_code ec;
  if (fs::is_regular_file(dir / "index.json", ec)) return true;
  for (const auto& entry : fs::directory_iterator(dir, ec))
    if (entry.is_directory(ec) && (fs::is_regular_file(entry.path() / "manifest.json", ec) ||
                                   fs::is_regular_file(entry.path() / "failure.json", ec)))
      return true;
  return false;
}

// Every deliverable asset folder of a library folder, by folder name; the others in `skipped`.
void addLibraryFolder(const fs::path& dir, BakedAssets& found) {
  std::vector<fs::path> folders;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (!name.empty() && name[0] != '.' && entry.is_directory(ec) &&
        (fs::exists(entry.path() / "manifest.json", ec) || fs::exists(entry.path() / "failure.json", ec)))
      folders.push_back(entry.path());
  }
  std::sort(folders.begin(), folders.end());
  std::size_t delivered = 0;
  for (const auto& folder : folders) {
    std::string problem;
    if (auto asset = loadAssetFolder(folder, problem)) {
      found.assets.push_back(std::move(*asset));
      ++delivered;
    } else {
      found.skipped.push_back(folder.string() + ": skipped: " + problem);
    }
  }
  if (delivered == 0)
    throw InputError({dir.string()}, "", "a library folder with no asset to deliver (none finished with a rock.glb)",
                     "bake the library with meshes and glb in every preset's export");
}

}  // namespace

BakedAssets findBakedAssets(const std::vector<fs::path>& sources) {
  BakedAssets found;
  for (const auto& source : sources) {
    std::error_code ec;
    const auto status = fs::status(source, ec);
    if (!fs::exists(status)) throw InputError({source.string()}, "", "does not exist", kWhatIsABake);
    if (!fs::is_directory(status)) throw InputError({source.string()}, "", "is not a folder", kWhatIsABake);
    if (fs::exists(source / "manifest.json", ec) || fs::exists(source / "failure.json", ec)) {
      std::string problem;
      auto asset = loadAssetFolder(source, problem);
      if (!asset) throw InputError({source.string()}, "", "cannot be delivered: " + problem, kWhatIsABake);
      found.assets.push_back(std::move(*asset));
    } else if (holdsAssetFolders(source)) {
      addLibraryFolder(source, found);
    } else {
      throw InputError({source.string()}, "", "is not a rockbake bake", kWhatIsABake);
    }
  }
  std::map<std::string, fs::path> seen;
  for (const auto& asset : found.assets) {
    const auto [it, fresh] = seen.emplace(asset.name, asset.dir);
    if (!fresh)
      throw InputError({asset.dir.string()}, "", "its asset '" + asset.name + "' is also " + it->second.string(),
                       "a Blender library holds one <name>.blend per asset: give each source once, with distinct "
                       "asset names");
  }
  return found;
}

}  // namespace rockbake
