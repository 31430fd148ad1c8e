// `rockbake lint` of a pack: pack.json against the folder (preset/preset_pack.h).
#include <algorithm>
#include <fstream>
#include <map>
#include <set>

#include <nlohmann/json.hpp>

#include "core/sha256.h"
#include "preset/catalogue.h"
#include "preset/preset_files.h"
#include "preset/preset_pack.h"

namespace rockbake {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const char* const kRepack = "the pack changed after it was made: get it again, or make it again with rockbake preset "
                            "pack PRESET -o DIR";

bool inside(const fs::path& path, const fs::path& root) {
  const fs::path relative = path.lexically_relative(root);
  return !relative.empty() && relative != "." && *relative.begin() != "..";
}

// Why `path` cannot name a file of a pack (absolute, `..`, …), or nothing.
std::optional<std::string> packPathProblem(const std::string& path) {
  if (path.empty()) return "an empty path";
  for (const char c : path)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f || c == '\\') return "a control byte or a backslash";
  const fs::path p(path);
  if (p.is_absolute()) return "an absolute path";
  for (const auto& part : p)
    if (part == ".." || part == "." || part.empty()) return "a path with '.', '..' or an empty part";
  if (p == kPackManifestFile) return "pack.json itself";
  return std::nullopt;
}

bool isSha256(const json& value) {
  if (!value.is_string()) return false;
  const std::string& s = value.get_ref<const std::string&>();
  return s.size() == 64 && std::all_of(s.begin(), s.end(), [](char c) {
           return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f');
         });
}

class PackChecker {
 public:
  explicit PackChecker(const fs::path& dir) : dir_(dir), manifest_((dir / kPackManifestFile).string()) {}
  PackCheck run();

 private:
  void problem(SourceLocation where, std::string key_path, std::string what, std::string hint = kRepack) {
    check_.problems.emplace_back(std::move(where), std::move(key_path), std::move(what), std::move(hint));
  }
  bool readManifest(json& manifest);
  void checkFile(const json& entry, const std::string& key_path);
  void checkFileBytes(const fs::path& file, const json& entry, const std::string& key_path);
  void checkUnlisted();
  void checkReach(const std::string& preset);

  fs::path dir_;
  std::string manifest_;
  std::set<std::string> listed_;
  PackCheck check_;
};

bool PackChecker::readManifest(json& manifest) {
  std::error_code ec;
  if (!fs::is_regular_file(fs::symlink_status(manifest_, ec))) {
    problem({dir_.string()}, "", "is not a pack: it holds no pack.json",
            "make a pack with rockbake preset pack PRESET -o DIR");
    return false;
  }
  try {
    std::ifstream in(manifest_);
    manifest = json::parse(in);
  } catch (const json::exception& e) {
    problem({manifest_}, "", std::string("is not JSON: ") + e.what(), kRepack);
    return false;
  }
  if (!manifest.is_object() || !manifest.contains("rockbake_pack")) {
    problem({manifest_}, "", "is not a rockbake pack's list (no rockbake_pack)", kRepack);
    return false;
  }
  if (manifest["rockbake_pack"] != kPackFormat) {
    problem({manifest_}, "rockbake_pack",
            "pack format " + manifest["rockbake_pack"].dump() + " is not supported; this rockbake reads " +
                std::to_string(kPackFormat),
            "use the rockbake the pack was made with, or make it again with this one");
    return false;
  }
  if (!manifest.contains("files") || !manifest["files"].is_array() || !manifest.contains("presets") ||
      !manifest["presets"].is_array() || manifest["presets"].empty()) {
    problem({manifest_}, "", "needs a list 'files' and a list 'presets' of at least one preset", kRepack);
    return false;
  }
  return true;
}

void PackChecker::checkFileBytes(const fs::path& file, const json& entry, const std::string& key_path) {
  std::error_code ec;
  const std::uintmax_t size = fs::file_size(file, ec);
  if (ec || !entry["size"].is_number_unsigned() || size != entry["size"].get<std::uintmax_t>()) {
    problem({file.string()}, "",
            "is " + std::to_string(size) + " bytes; pack.json (" + key_path + ".size) says " + entry["size"].dump());
    return;
  }
  const std::string sha = sha256File(file);
  if (sha != entry["sha256"].get<std::string>())
    problem({file.string()}, "",
            "does not match its SHA-256 in pack.json (" + key_path + ".sha256): it is " + sha + ", not " +
                entry["sha256"].get<std::string>());
}

void PackChecker::checkFile(const json& entry, const std::string& key_path) {
  if (!entry.is_object() || !entry.contains("path") || !entry["path"].is_string() || !entry.contains("size") ||
      !isSha256(entry.value("sha256", json()))) {
    problem({manifest_}, key_path, "expected {path, size, sha256} (a SHA-256 of 64 hex digits)");
    return;
  }
  const std::string path = entry["path"].get<std::string>();
  if (const auto why = packPathProblem(path)) {
    problem({manifest_}, key_path + ".path", "'" + path + "' is " + *why + ", not a file in the pack",
            "a pack lists only files inside itself, by relative paths");
    return;
  }
  if (!listed_.insert(path).second) {
    problem({manifest_}, key_path + ".path", "'" + path + "' is listed twice");
    return;
  }
  // Every folder on the way and the file itself: plain, no symbolic link (which could reach outside).
  fs::path on_the_way = dir_;
  std::error_code ec;
  for (const auto& part : fs::path(path)) {
    on_the_way /= part;
    const fs::file_status status = fs::symlink_status(on_the_way, ec);
    if (status.type() == fs::file_type::not_found) {
      problem({on_the_way.string()}, "", "is missing; pack.json lists " + path + " (" + key_path + ")");
      return;
    }
    if (fs::is_symlink(status)) {
      problem({on_the_way.string()}, "", "is a symbolic link; a pack holds plain files and folders only",
              "replace the link by the file, or make the pack again");
      return;
    }
  }
  if (!fs::is_regular_file(fs::symlink_status(on_the_way, ec))) {
    problem({on_the_way.string()}, "", "is not a plain file; pack.json lists it (" + key_path + ")");
    return;
  }
  checkFileBytes(on_the_way, entry, key_path);
}

void PackChecker::checkUnlisted() {
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(dir_, ec); !ec && it != fs::recursive_directory_iterator();
       it.increment(ec)) {
    const std::string relative = it->path().lexically_relative(dir_).generic_string();
    if (relative == kPackManifestFile) continue;
    const fs::file_status status = it->symlink_status(ec);
    if (fs::is_directory(status)) continue;
    if (listed_.count(relative)) continue;  // a listed link or odd file is checkFile's
    if (fs::is_symlink(status))
      problem({it->path().string()}, "", "is a symbolic link that pack.json does not list; a pack holds plain files",
              "remove it");
    else
      problem({it->path().string()}, "", "is not listed in pack.json; a pack holds only what its presets reach",
              "remove it, or make the pack again");
  }
}

// What the preset reaches lies in the pack and is listed (a pack is self-contained).
void PackChecker::checkReach(const std::string& preset) {
  PresetFiles files;
  try {
    files = presetFiles(dir_ / preset);
  } catch (const InputError&) {
    return;  // the preset's lint reports it
  }
  const fs::path root = fs::weakly_canonical(dir_);
  for (const PresetFileRef& ref : files.refs) {
    if (ref.catalogue) {
      problem(ref.where, ref.key_path,
              "names an installed catalogue preset; a pack holds the bases its presets extend",
              "make the pack again with rockbake preset pack: it copies the base into the pack");
      continue;
    }
    std::error_code ec;
    const fs::path target = fs::weakly_canonical(ref.target, ec);
    if (ec || !inside(target, root)) {
      problem(ref.where, ref.key_path, "'" + ref.written + "' reaches outside the pack (to " + ref.target.string() + ")",
              "a pack's presets may name only files in the pack: make the pack again");
      continue;
    }
    const std::string relative = target.lexically_relative(root).generic_string();
    if (!listed_.count(relative))
      problem(ref.where, ref.key_path, "names " + relative + ", which pack.json does not list");
  }
}

PackCheck PackChecker::run() {
  json manifest;
  if (!readManifest(manifest)) return check_;
  const json& files = manifest["files"];
  for (std::size_t i = 0; i < files.size(); ++i) checkFile(files[i], "files." + std::to_string(i));
  check_.files = listed_.size();
  checkUnlisted();
  const json& presets = manifest["presets"];
  for (std::size_t i = 0; i < presets.size(); ++i) {
    const std::string key_path = "presets." + std::to_string(i);
    if (!presets[i].is_string() || !listed_.count(presets[i].get<std::string>())) {
      problem({manifest_}, key_path, presets[i].dump() + " is not a file pack.json lists");
      continue;
    }
    check_.presets.push_back(presets[i].get<std::string>());
    checkReach(check_.presets.back());
  }
  return check_;
}

}  // namespace

PackCheck checkPack(const fs::path& dir) {
  return PackChecker(dir).run();
}

}  // namespace rockbake
