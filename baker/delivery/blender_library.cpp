#include "delivery/blender_library.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <mutex>
#include <set>
#include <thread>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "core/error.h"
#include "delivery/blender_program.h"
#include "platform/atomic_file.h"
#include "platform/data_dir.h"
#include "platform/input_file.h"

namespace rockbake {

namespace fs = std::filesystem;

namespace {

constexpr const char* kResultPrefix = "ROCKBAKE_BLENDER_RESULT ";  // the script's last line
constexpr const char* kErrorPrefix = "ROCKBAKE_BLENDER_ERROR ";    // what went wrong, when it failed
constexpr const char* kPartialSuffix = ".partial.blend";           // .<asset>.<pid>.partial.blend
constexpr const char* kLockFile = ".rockbake_blender_library.lock";
const std::chrono::seconds kBlenderTimeout(30 * 60);

const char* const kNotOursHint =
    "rockbake writes a Blender library only into a new or empty folder, or over one it wrote (holding "
    "rockbake_blender_library.json): move it away or give another -o";

bool isBlendOfAnAsset(const std::string& file) {
  const std::string stem = file.size() > 6 ? file.substr(0, file.size() - 6) : std::string();
  return file.size() > 6 && file.compare(file.size() - 6, 6, ".blend") == 0 && stem.size() <= 64 &&
         std::all_of(stem.begin(), stem.end(),
                     [](char c) { return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || c == '-'; });
}

// The marker's JSON, or null when it is not one rockbake wrote.
nlohmann::json readMarker(const fs::path& file) {
  try {
    const InputFile in(file, "");
    if (in.size() > (std::uint64_t(16) << 20)) return nullptr;
    nlohmann::json marker = nlohmann::json::parse(in.read(0, in.size()), nullptr, false);
    if (marker.is_object() && marker.value("rockbake_blender_library", 0) == 1) return marker;
  } catch (const InputError&) {
  }
  return nullptr;
}

std::string thousands(std::uint64_t n) {
  std::string digits = std::to_string(n), out;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return out;
}

// flock on OUT/.rockbake_blender_library.lock while a run writes OUT: one run at a time. The kernel
// drops it when the process dies, so a killed run's lock is no obstacle.
class LibraryLock {
 public:
  explicit LibraryLock(const fs::path& out) {
    const fs::path file = out / kLockFile;
    // O_NOFOLLOW: a link planted as the lock would lock a file elsewhere; O_NONBLOCK: a FIFO would wait.
    fd_ = open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK, 0644);
    struct stat st {};
    if (fd_ < 0 || fstat(fd_, &st) != 0 || !S_ISREG(st.st_mode)) {
      const std::string why = fd_ < 0 ? std::strerror(errno) : "not a regular file";
      if (fd_ >= 0) close(fd_);
      throw InputError({file.string()}, "", "cannot be opened as the library's lock: " + why,
                       "remove it and run again");
    }
    while (flock(fd_, LOCK_EX | LOCK_NB) != 0) {
      if (errno == EINTR) continue;
      close(fd_);
      throw InputError({out.string()}, "", "another rockbake blender-library is writing this library",
                       "wait for it to finish, or write into another folder (-o)");
    }
  }
  ~LibraryLock() { close(fd_); }
  LibraryLock(const LibraryLock&) = delete;
  LibraryLock& operator=(const LibraryLock&) = delete;

 private:
  int fd_ = -1;
};

// The file's bytes on disk before it is renamed into place, as writeFileAtomically does.
bool flushed(const fs::path& file) {
  const int fd = open(file.c_str(), O_RDONLY | O_CLOEXEC | O_NOFOLLOW);
  if (fd < 0) return false;
  const bool ok = fsync(fd) == 0;
  close(fd);
  return ok;
}

}  // namespace

LibraryFolder checkLibraryFolder(const fs::path& out) {
  LibraryFolder folder;
  std::error_code ec;
  const auto status = fs::status(out, ec);
  if (!fs::exists(status)) return folder;
  if (!fs::is_directory(status))
    throw InputError({out.string()}, "", "is a file, not a folder", "give -o a folder for the Blender library");
  bool empty = true;  // but for the lock of a run that found it empty
  for (const auto& entry : fs::directory_iterator(out, ec)) empty = empty && entry.path().filename() == kLockFile;
  if (empty) return folder;
  const nlohmann::json marker = readMarker(out / kBlenderLibraryMarker);
  if (marker.is_null()) {
    const bool blender_library = fs::exists(out / kBlenderCatalogFile, ec);
    throw InputError({out.string()}, "",
                     blender_library ? "is a Blender asset library rockbake did not write (it holds no "
                                       "rockbake_blender_library.json)"
                                     : "is a folder that is not a Blender library rockbake wrote",
                     kNotOursHint);
  }
  folder.ours = true;
  if (marker.contains("assets") && marker["assets"].is_array())
    for (const auto& asset : marker["assets"])
      if (asset.is_object() && asset.contains("file") && asset["file"].is_string() &&
          isBlendOfAnAsset(asset["file"].get<std::string>()))
        folder.previous_files.push_back(asset["file"].get<std::string>());
  return folder;
}

std::string assetDescription(const BakedAsset& asset) {
  const nlohmann::json& a = asset.asset;
  const nlohmann::json job = asset.inputs.value("job", nlohmann::json::object());
  std::string preset = job.is_object() ? job.value("preset", std::string()) : std::string();
  preset = fs::path(preset).stem().string();
  std::string from = preset.empty() ? "" : " from the preset " + preset;
  const std::string wedge = job.is_object() && job.contains("wedge") && job["wedge"].is_string()
                                ? job["wedge"].get<std::string>()
                                : std::string();
  if (!wedge.empty()) from += ", wedge " + wedge;
  if (asset.inputs.contains("seed") && asset.inputs["seed"].is_number_integer() && asset.inputs["seed"] >= 0)
    from += ", seed " + std::to_string(asset.inputs["seed"].get<std::uint64_t>());
  const auto& size = a["size_m"];
  std::string text =
      fmt::format("{}: a weathered rock baked by rockbake{}. {:.2f} × {:.2f} × {:.2f} m (x × y × z, z up)", asset.name,
                  from, size[0].get<double>(), size[1].get<double>(), size[2].get<double>());
  const auto& lod0 = a["lods"][0];
  if (lod0.contains("triangles") && lod0["triangles"].is_number_integer() && lod0["triangles"] >= 0)
    text += "; LOD0 " + thousands(lod0["triangles"].get<std::uint64_t>()) + " triangles";
  if (a.contains("clasts") && a["clasts"].is_object() && a["clasts"].value("stones", 0) > 0)
    text += fmt::format(" and {} stones on its apron", a["clasts"].value("stones", 0));
  std::vector<std::string> more;
  if (a["lods"].size() > 1)
    more.push_back(a["lods"].size() == 2 ? "LOD1" : fmt::format("LOD1 to LOD{}", a["lods"].size() - 1));
  if (a.contains("collision") && a["collision"].is_object())
    more.push_back(fmt::format("{} collision hulls", a["collision"].value("hull_count", 0)));
  if (!more.empty()) text += ". Its .blend also holds " + fmt::format("{}", fmt::join(more, " and "));
  return text + ".";
}

nlohmann::json blenderJob(const BakedAsset& asset, const BlenderCatalog& catalog, const fs::path& output) {
  const nlohmann::json& a = asset.asset;
  nlohmann::json lods = nlohmann::json::array();
  for (std::size_t i = 0; i < a["lods"].size(); ++i)
    lods.push_back({{"level", a["lods"][i].value("level", int(i))}, {"file", a["lods"][i]["file"]}});
  nlohmann::json collision = nullptr;
  if (a.contains("collision") && a["collision"].is_object())
    collision = {{"file", a["collision"]["file"]}, {"naming", a["collision"].value("naming", std::string("unreal"))}};
  std::vector<std::string> tags;
  if (a.contains("tags") && a["tags"].is_array())
    for (const auto& tag : a["tags"])
      if (tag.is_string() && !tag.get<std::string>().empty() &&
          std::find(tags.begin(), tags.end(), tag.get<std::string>()) == tags.end())
        tags.push_back(tag.get<std::string>().substr(0, 63));
  const std::string input_hash = a.value("input_hash", std::string());
  return {{"name", asset.name},
          {"asset_dir", asset.dir.string()},
          {"output", output.string()},
          {"lods", lods},
          {"collision", collision},
          {"preview", asset.preview.empty() ? nlohmann::json() : nlohmann::json(asset.preview)},
          {"catalog", {{"id", catalog.uuid}, {"path", catalog.path}, {"simple_name", catalog.simple_name}}},
          {"description", assetDescription(asset)},
          {"author", "rockbake"},
          {"tags", tags},
          {"size_m", a["size_m"]},
          {"properties",
           {{"rockbake_asset", asset.name},
            {"rockbake_catalog", catalog.path},
            {"rockbake_size_m", a["size_m"]},
            {"rockbake_units_per_meter", a.value("units_per_meter", 1.0)},
            {"rockbake_input_hash", input_hash},
            {"rockbake_version", ROCKBAKE_VERSION}}}};
}

namespace {

// One asset's .blend, as the script reports it (or why it failed).
struct Delivery {
  bool ok = false;
  std::string message;    // why not
  nlohmann::json result;  // the script's report
  double seconds = 0.0;
};

// The rest of the last line of the output starting with `prefix`; empty when none.
std::string scriptLine(const std::string& output, const std::string& prefix) {
  std::size_t at = output.rfind("\n" + prefix);
  if (at != std::string::npos)
    ++at;
  else if (output.rfind(prefix, 0) == 0)
    at = 0;
  else
    return {};
  const std::size_t begin = at + prefix.size();
  const std::size_t end = output.find('\n', begin);
  return output.substr(begin, end == std::string::npos ? std::string::npos : end - begin);
}

// The script's report, or null.
nlohmann::json scriptResult(const std::string& output) {
  nlohmann::json result = nlohmann::json::parse(scriptLine(output, kResultPrefix), nullptr, false);
  return result.is_discarded() ? nlohmann::json() : result;
}

// The last lines of what Blender said, for a message.
std::string lastLines(const std::string& output, std::size_t count) {
  std::size_t at = output.size();
  while (count-- > 0 && at > 0) {
    const std::size_t nl = output.rfind('\n', at > 1 ? at - 2 : 0);
    if (nl == std::string::npos || at <= 1) {
      at = 0;
      break;
    }
    at = nl + 1;
  }
  return output.substr(at);
}

// Why Blender wrote no .blend: the script's own sentence when it gave one, else the end of what Blender said.
std::string failureMessage(const BlenderRun& run) {
  if (run.timed_out) return fmt::format("Blender did not finish within {} s and was killed", kBlenderTimeout.count());
  if (run.exit_code < 0) return "Blender was killed by a signal";
  const std::string error = scriptLine(run.output, kErrorPrefix);
  if (!error.empty()) return "Blender failed: " + escapeControlBytes(error) + " (rockbake -v shows all it said)";
  return fmt::format("Blender failed (exit status {}); it said:\n{}", run.exit_code,
                     escapeControlBytesKeepingLines(lastLines(run.output, 12)));
}

Delivery deliverOne(const BlenderProgram& blender, const fs::path& script, const BakedAsset& asset,
                    const fs::path& out_dir, int threads) {
  const BlenderCatalog catalog = blenderCatalog(asset.catalog);
  // Absolute: Blender saves only to an absolute path.
  const fs::path partial = fs::absolute(out_dir / fmt::format(".{}.{}{}", asset.name, ::getpid(), kPartialSuffix));
  const fs::path target = out_dir / (asset.name + ".blend");
  std::error_code ec;
  fs::remove(partial, ec);
  const BlenderRun run =
      runBlenderScript(blender, script, {blenderJob(asset, catalog, partial).dump()}, threads, kBlenderTimeout);
  Delivery delivery;
  delivery.seconds = run.seconds;
  delivery.result = scriptResult(run.output);
  spdlog::debug("{}: Blender said:\n{}", asset.name, escapeControlBytesKeepingLines(run.output));
  if (run.exit_code == 0 && !delivery.result.is_null() && fs::is_regular_file(partial, ec) &&
      fs::file_size(partial, ec) > 0 && flushed(partial)) {
    fs::rename(partial, target, ec);
    if (!ec) {
      delivery.ok = true;
      return delivery;
    }
    delivery.message = "cannot rename " + partial.string() + " to " + target.string() + ": " + ec.message();
  } else {
    delivery.message = failureMessage(run);
  }
  fs::remove(partial, ec);
  fs::remove(fs::path(partial.string() + "@"), ec);  // Blender's own temporary while it saves
  return delivery;
}

// Each asset's .blend, `jobs` Blender processes at once; deliveries in the assets' order.
std::vector<Delivery> deliverAll(const BlenderProgram& blender, const fs::path& script,
                                 const std::vector<BakedAsset>& assets, const fs::path& out_dir, int jobs,
                                 int threads) {
  std::vector<Delivery> deliveries(assets.size());
  std::atomic<std::size_t> next{0};
  std::mutex log;
  const auto work = [&] {
    for (std::size_t i; (i = next.fetch_add(1)) < assets.size();) {
      try {
        deliveries[i] = deliverOne(blender, script, assets[i], out_dir, threads);
      } catch (const std::exception& e) {
        deliveries[i].message = e.what();
      }
      const std::lock_guard<std::mutex> lock(log);
      if (deliveries[i].ok)
        spdlog::info("[{}/{}] {}.blend ({}, preview {}) in {:.1f} s", i + 1, assets.size(), assets[i].name,
                     assets[i].catalog, deliveries[i].result.value("preview", std::string("?")), deliveries[i].seconds);
      else
        spdlog::error("{}: {}", assets[i].dir.string(), deliveries[i].message);
      if (deliveries[i].result.is_object() && deliveries[i].result.contains("warnings"))
        for (const auto& warning : deliveries[i].result["warnings"])
          if (warning.is_string()) spdlog::warn("{}: {}", assets[i].name, warning.get<std::string>());
    }
  };
  std::vector<std::thread> workers;
  for (int j = 1; j < std::max(1, std::min<int>(jobs, int(assets.size()))); ++j) workers.emplace_back(work);
  work();
  for (auto& worker : workers) worker.join();
  return deliveries;
}

// Leftovers of a killed run: the hidden temporaries of the .blend files.
void removeLeftovers(const fs::path& out_dir) {
  std::error_code ec;
  std::vector<fs::path> leftovers;
  for (const auto& entry : fs::directory_iterator(out_dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.size() > 1 && name[0] == '.' &&
        (name.find(kPartialSuffix) != std::string::npos || name.find(".tmp-") != std::string::npos))
      leftovers.push_back(entry.path());
  }
  for (const auto& path : leftovers) fs::remove(path, ec);
}

// The marker: every asset of this run, with its outcome ("pending" while the run goes on: `deliveries`
// empty), and the `earlier` .blend files a run before left that are to be removed.
nlohmann::json markerJson(const BlenderProgram& blender, const std::vector<BakedAsset>& assets,
                          const std::vector<Delivery>& deliveries, const std::vector<std::string>& earlier = {}) {
  nlohmann::json list = nlohmann::json::array();
  for (std::size_t i = 0; i < assets.size() && deliveries.empty(); ++i)
    list.push_back({{"name", assets[i].name},
                    {"file", assets[i].name + ".blend"},
                    {"catalog", assets[i].catalog},
                    {"source", assets[i].dir.string()},
                    {"status", "pending"}});
  for (const auto& file : earlier) list.push_back({{"file", file}, {"status", "earlier"}});
  for (std::size_t i = 0; i < assets.size() && !deliveries.empty(); ++i) {
    nlohmann::json entry = {{"name", assets[i].name},
                            {"file", assets[i].name + ".blend"},
                            {"catalog", assets[i].catalog},
                            {"catalog_id", catalogUuid(assets[i].catalog)},
                            {"source", assets[i].dir.string()},
                            {"input_hash", assets[i].asset.value("input_hash", std::string())},
                            {"status", deliveries[i].ok ? "ok" : "failed"}};
    if (deliveries[i].ok) entry["preview"] = deliveries[i].result.value("preview", std::string());
    if (!deliveries[i].ok) entry["message"] = deliveries[i].message;
    list.push_back(entry);
  }
  return {{"rockbake_blender_library", 1},
          {"baker_version", ROCKBAKE_VERSION},
          {"blender", blender.version},
          {"catalogs", kBlenderCatalogFile},
          {"assets", list}};
}

}  // namespace

BlenderLibraryResult writeBlenderLibrary(const BlenderLibraryOptions& options) {
  // Everything checked before anything is written.
  const BakedAssets found = findBakedAssets(options.sources);
  const BlenderProgram blender = findBlender(options.blender);
  const fs::path script = requireDataPath(kBlenderLibraryScript);
  const fs::path out = options.out_dir;
  checkLibraryFolder(out);
  std::error_code ec;
  fs::create_directories(out, ec);
  if (ec) throw std::runtime_error("cannot make the folder " + out.string() + ": " + ec.message());
  const LibraryLock lock(out);
  const LibraryFolder folder = checkLibraryFolder(out);  // again, now that no other run can change it
  for (const auto& skipped : found.skipped) spdlog::warn("{}", skipped);
  spdlog::info("{} assets → {} ({}, {} at once)", found.assets.size(), out.string(), blender.version, options.jobs);

  // From here the folder reads as rockbake's, listing every .blend this run may leave, so that a re-run
  // after a kill replaces it and removes what it no longer needs.
  std::set<std::string> current;
  for (const auto& asset : found.assets) current.insert(asset.name + ".blend");
  std::vector<std::string> earlier;
  for (const auto& file : folder.previous_files)
    if (!current.count(file)) earlier.push_back(file);
  writeFileAtomically(out / kBlenderLibraryMarker, markerJson(blender, found.assets, {}, earlier).dump(2) + "\n");
  removeLeftovers(out);

  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  const int jobs = std::max(1, options.jobs);
  const int threads = std::max(1, (options.threads > 0 ? options.threads : int(cores)) / jobs);
  const auto deliveries = deliverAll(blender, script, found.assets, out, jobs, threads);

  std::vector<std::string> paths;
  for (const auto& asset : found.assets) paths.push_back(asset.catalog);
  writeFileAtomically(out / kBlenderCatalogFile, catalogFileText(catalogsWithParents(paths)));
  BlenderLibraryResult result;
  for (const auto& file : earlier)
    if (fs::remove(out / file, ec)) ++result.removed;
  writeFileAtomically(out / kBlenderLibraryMarker, markerJson(blender, found.assets, deliveries).dump(2) + "\n");

  for (const auto& delivery : deliveries) (delivery.ok ? result.written : result.failed) += 1;
  result.skipped = found.skipped.size();
  return result;
}

}  // namespace rockbake
