#include "pipeline/library_index.h"

#include <algorithm>
#include <cctype>
#include <exception>
#include <fstream>
#include <set>

#include <spdlog/spdlog.h>
#include <nlohmann/json.hpp>

#include "pipeline/asset_json.h"
#include "pipeline/manifest.h"
#include "platform/atomic_file.h"
#include "platform/png_image.h"
#include "render/contact_sheet.h"

namespace rockbake {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using nlohmann::ordered_json;

std::optional<json> readJson(const fs::path& file, std::string* problem = nullptr) {
  std::ifstream in(file);
  if (!in) return std::nullopt;
  try {
    return json::parse(in);
  } catch (const json::exception& e) {
    if (problem) *problem = e.what();
    return std::nullopt;
  }
}

// Names in natural order: runs of digits compare as numbers, so goblin-s9
// comes before goblin-s10 (then plain text order breaks ties, e.g. s01 / s1).
bool naturalLess(const std::string& a, const std::string& b) {
  std::size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    const bool da = std::isdigit(static_cast<unsigned char>(a[i])), db = std::isdigit(static_cast<unsigned char>(b[j]));
    if (da && db) {
      std::size_t ie = i, je = j;
      while (ie < a.size() && std::isdigit(static_cast<unsigned char>(a[ie]))) ++ie;
      while (je < b.size() && std::isdigit(static_cast<unsigned char>(b[je]))) ++je;
      // Compare the numbers without their leading zeros: longer is larger, else digit by digit.
      std::size_t ia = i, jb = j;
      while (ia + 1 < ie && a[ia] == '0') ++ia;
      while (jb + 1 < je && b[jb] == '0') ++jb;
      if (ie - ia != je - jb) return ie - ia < je - jb;
      if (const int c = a.compare(ia, ie - ia, b, jb, je - jb); c != 0) return c < 0;
      i = ie, j = je;
    } else {
      if (a[i] != b[j]) return a[i] < b[j];
      ++i, ++j;
    }
  }
  if ((i < a.size()) != (j < b.size())) return j < b.size();
  return a < b;
}

// One folder of OUT as the index lists it.
struct IndexEntry {
  enum class Status { Ok, SkippedResumed, Failed, Damaged };
  Status status = Status::Ok;
  ordered_json asset;
  json library;  // {file, sha256} of the library it came from, or null
  ContactSheetItem tile;
};

std::vector<std::string> folderNames(const fs::path& out_dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(out_dir)) {
    const std::string name = entry.path().filename().string();
    if (entry.is_directory() && !name.empty() && name.front() != '.') names.push_back(name);
  }
  std::sort(names.begin(), names.end(), naturalLess);
  return names;
}

IndexEntry damaged(const std::string& name, const std::string& message) {
  spdlog::warn("{}: damaged: {}; bake it again", name, message);
  return {IndexEntry::Status::Damaged,
          {{"name", name}, {"status", "damaged"}, {"message", message}},
          nullptr,
          {name, fs::path(), "damaged"}};
}

IndexEntry finishedAsset(const fs::path& dir, const std::string& name, const json& manifest,
                         const std::map<std::string, std::string>& run_status) {
  const json& inputs = manifest["inputs"];
  const auto run = run_status.find(name);
  const std::string status = run != run_status.end() ? run->second : "ok";
  bool rendered = false, described = false, movie = false;
  for (const auto& output : manifest.value("outputs", json::array())) {
    rendered = rendered || (output.is_object() && output.value("path", "") == "render.png");
    movie = movie || (output.is_object() && output.value("path", "") == "turntable.mp4");
    described = described || (output.is_object() && output.value("path", "") == kAssetFile);
  }
  IndexEntry entry;
  entry.status = status == "skipped-resumed" ? IndexEntry::Status::SkippedResumed : IndexEntry::Status::Ok;
  entry.asset["name"] = name;
  entry.asset["status"] = status;
  entry.asset["job"] = inputs.value("job", json(nullptr));
  entry.asset["input_hash"] = inputs.value("input_hash", "");
  entry.asset["manifest"] = name + "/" + kManifestFile;
  entry.asset["render"] = rendered ? json(name + "/render.png") : json(nullptr);
  entry.asset["movie"] = movie ? json(name + "/turntable.mp4") : json(nullptr);
  entry.asset["asset"] = described ? json(name + "/" + kAssetFile) : json(nullptr);
  entry.library = inputs.value("library", json(nullptr));
  entry.tile = {name, rendered ? dir / "render.png" : fs::path(), "no render"};
  return entry;
}

IndexEntry failedJob(const std::string& name, const json& failure) {
  IndexEntry entry;
  entry.status = IndexEntry::Status::Failed;
  entry.asset["name"] = name;
  entry.asset["status"] = "failed";
  entry.asset["message"] = failure["message"];
  entry.asset["job"] = failure.value("inputs", json::object()).value("job", json(nullptr));
  entry.asset["failure"] = name + "/" + kFailureFile;
  entry.library = failure.value("inputs", json::object()).value("library", json(nullptr));
  entry.tile = {name, fs::path(), "failed"};
  return entry;
}

// The folder's entry: a finished asset (manifest.json), a failed job (failure.json), damaged (either there
// but unreadable, or of the wrong shape), or nothing (not an asset folder, or a bake not finished).
std::optional<IndexEntry> readFolder(const fs::path& out_dir, const std::string& name,
                                     const std::map<std::string, std::string>& run_status) {
  const fs::path dir = out_dir / name;
  std::string manifest_problem, failure_problem;
  const auto manifest = readJson(dir / kManifestFile, &manifest_problem);
  const auto failure = manifest ? std::nullopt : readJson(dir / kFailureFile, &failure_problem);
  const bool manifest_ok = manifest && manifest->is_object() && manifest->contains("inputs") &&
                           (*manifest)["inputs"].is_object() && manifest->value("outputs", json::array()).is_array();
  const bool failure_ok = failure && failure->is_object() && failure->contains("message");
  if (!manifest_ok && !failure_ok && (fs::exists(dir / kManifestFile) || fs::exists(dir / kFailureFile))) {
    // There, but unreadable: cut off or garbled. Never left out silently.
    const char* file = fs::exists(dir / kManifestFile) ? kManifestFile : kFailureFile;
    const std::string& why = fs::exists(dir / kManifestFile) ? manifest_problem : failure_problem;
    return damaged(name,
                   std::string(file) + " cannot be read" + (why.empty() ? " (not what a bake writes)" : ": " + why));
  }
  try {
    if (manifest_ok) return finishedAsset(dir, name, *manifest, run_status);
    if (failure_ok) return failedJob(name, *failure);
    return std::nullopt;
  } catch (const json::exception& e) {  // a value of another type
    return damaged(name, e.what());
  }
}

}  // namespace

IndexCounts writeLibraryIndex(const fs::path& out_dir, const std::map<std::string, std::string>& run_status,
                              const ordered_json& timings) {
  IndexCounts counts;
  ordered_json assets = ordered_json::array();
  std::set<std::pair<std::string, std::string>> libraries;
  std::vector<ContactSheetItem> sheet;
  for (const auto& name : folderNames(out_dir)) {
    std::optional<IndexEntry> entry = readFolder(out_dir, name, run_status);
    if (!entry) continue;
    switch (entry->status) {
      case IndexEntry::Status::Ok:
        ++counts.ok;
        break;
      case IndexEntry::Status::SkippedResumed:
        ++counts.skipped_resumed;
        break;
      case IndexEntry::Status::Failed:
        ++counts.failed;
        break;
      case IndexEntry::Status::Damaged:
        ++counts.damaged;
        break;
    }
    const json& library = entry->library;
    if (library.is_object() && library.value("file", json()).is_string() && library.value("sha256", json()).is_string())
      libraries.emplace(library.value("file", ""), library.value("sha256", ""));
    assets.push_back(std::move(entry->asset));
    sheet.push_back(std::move(entry->tile));
  }

  // The index is written even when the sheet cannot be (a missing font, a full disk); the error follows it.
  bool with_sheet = false;
  std::exception_ptr sheet_error;
  try {
    fs::remove(out_dir / kContactSheetFile);  // no stale sheet of other assets, whatever happens below
    if (!sheet.empty()) writePngRgb(out_dir / kContactSheetFile, makeContactSheet(sheet)), with_sheet = true;
  } catch (const std::exception&) {
    sheet_error = std::current_exception();
  }

  ordered_json index;
  index["rockbake_index"] = 1;
  index["baker_version"] = ROCKBAKE_VERSION;
  index["libraries"] = ordered_json::array();
  for (const auto& [file, sha] : libraries) index["libraries"].push_back({{"file", file}, {"sha256", sha}});
  index["assets"] = assets;
  index["counts"] = {{"ok", counts.ok},
                     {"skipped-resumed", counts.skipped_resumed},
                     {"failed", counts.failed},
                     {"damaged", counts.damaged}};
  index["contact_sheet"] = with_sheet ? json(kContactSheetFile) : json(nullptr);
  index["timings"] = timings;
  index["host"] = hostName();
  writeFileAtomically(out_dir / kIndexFile, index.dump(2) + "\n");
  if (sheet_error) std::rethrow_exception(sheet_error);
  return counts;
}

}  // namespace rockbake
