#include "preset/preset_pack.h"

#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/sha256.h"
#include "platform/atomic_file.h"
#include "preset/catalogue.h"
#include "preset/load_preset.h"
#include "preset/preset_files.h"
#include "preset/preset_tree.h"

namespace rockbake {
namespace {

namespace fs = std::filesystem;
using nlohmann::ordered_json;

// `path` lies inside `root` (both canonical), and is not `root` itself.
bool inside(const fs::path& path, const fs::path& root) {
  const fs::path relative = path.lexically_relative(root);
  return !relative.empty() && relative != "." && *relative.begin() != "..";
}

fs::path canonicalOrSelf(const fs::path& path) {
  std::error_code ec;
  const fs::path canonical = fs::weakly_canonical(path, ec);
  return ec ? path : canonical;
}

std::string readBytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + file.string() + ": " + std::strerror(errno));
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

// A YAML scalar that reads back as `text`: plain when that is safe, else single-quoted.
std::string yamlScalar(const std::string& text) {
  const bool plain = !text.empty() && std::all_of(text.begin(), text.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '-' || c == '/';
  });
  if (plain) return text;
  std::string quoted = "'";
  for (const char c : text) quoted += c == '\'' ? std::string("''") : std::string(1, c);
  return quoted + "'";
}

// How many bytes the scalar written at `offset` spans: a quoted one to its closing quote, a plain one
// its own text. Nothing when the text there is not the value (a plain scalar folded over lines).
std::optional<std::size_t> scalarLength(const std::string& text, std::size_t offset, const std::string& value) {
  if (offset >= text.size()) return std::nullopt;
  const char quote = text[offset];
  if (quote == '\'' || quote == '"') {
    for (std::size_t i = offset + 1; i < text.size(); ++i) {
      if (quote == '"' && text[i] == '\\') {
        ++i;
      } else if (text[i] == quote) {
        if (quote == '\'' && i + 1 < text.size() && text[i + 1] == '\'') {
          ++i;
          continue;
        }
        return i + 1 - offset;
      } else if (text[i] == '\n') {
        return std::nullopt;
      }
    }
    return std::nullopt;
  }
  if (text.compare(offset, value.size(), value) == 0) return value.size();
  return std::nullopt;
}

// A value in a copied file rewritten to name the pack's copy of what it names.
struct Edit {
  std::size_t offset = 0;
  std::string written, replacement;
  SourceLocation where;
  std::string key_path;
};

struct PackEntry {
  fs::path source;            // read from
  fs::path canonical;         // the file itself, links resolved
  std::string role;           // "preset", "base" or the key path that names it
  std::string catalogue;      // "rockbake:NAME" for a copy of an installed catalogue file
  std::map<std::size_t, Edit> edits;  // by offset
};

// What goes into the pack, and where: every preset, base and named file, by its path in the pack.
class PackPlan {
 public:
  explicit PackPlan(const fs::path& folder) : folder_(folder), root_(canonicalOrSelf(folder)) {}

  void addPreset(const fs::path& preset);
  const std::map<fs::path, PackEntry>& entries() const { return entries_; }

 private:
  enum class Root { Preset, Catalogue };
  fs::path inPack(const PresetFileRef& ref, Root root);
  fs::path catalogueRoot(const PresetFileRef& ref);
  void add(const fs::path& in_pack, const fs::path& source, const std::string& role, const std::string& catalogue);

  fs::path folder_, root_;  // the presets' folder, as given and canonical
  fs::path catalogue_root_;
  std::map<fs::path, PackEntry> entries_;
};

fs::path PackPlan::catalogueRoot(const PresetFileRef& ref) {
  if (catalogue_root_.empty()) {
    const fs::path dir = catalogueDir();
    if (dir.empty())
      throw InputError(ref.where, ref.key_path, "cannot find the installed catalogue",
                       "set ROCKBAKE_DATA_DIR to an installed <prefix>/share/rockbake");
    catalogue_root_ = canonicalOrSelf(dir);
  }
  return catalogue_root_;
}

// Where `ref`'s target goes in the pack, when it may go there: a file of the presets' folder (a
// preset's own files) or of the installed catalogue (a catalogue base's files, or a rockbake:NAME).
fs::path PackPlan::inPack(const PresetFileRef& ref, Root root) {
  std::error_code ec;
  if (!fs::is_regular_file(ref.target, ec))
    throw InputError(ref.where, ref.key_path, "no file at " + ref.target.string(),
                     "the pack needs every file the preset names: restore it, or fix the path (relative to " +
                         ref.from.parent_path().string() + ")");
  const fs::path target = canonicalOrSelf(ref.target);
  if (root == Root::Catalogue || ref.catalogue) {
    const fs::path catalogue = catalogueRoot(ref);
    if (!inside(target, catalogue))
      throw InputError(ref.where, ref.key_path,
                       "reaches outside the installed catalogue " + catalogue.string() + ": " + target.string(),
                       "reinstall rockbake: its catalogue files name only each other");
    return fs::path(kPackCatalogueFolder) / target.lexically_relative(catalogue);
  }
  if (!inside(target, root_))
    throw InputError(ref.where, ref.key_path,
                     "'" + ref.written + "' reaches outside the preset's folder " + root_.string() + " (to " +
                         target.string() + ")",
                     "a shared preset may name only files in its own folder, and installed presets as rockbake:NAME: "
                     "copy the file into that folder");
  return target.lexically_relative(root_);
}

void PackPlan::add(const fs::path& in_pack, const fs::path& source, const std::string& role,
                   const std::string& catalogue) {
  const fs::path canonical = canonicalOrSelf(source);
  const auto [it, added] = entries_.try_emplace(in_pack, PackEntry{source, canonical, role, catalogue, {}});
  if (added) return;
  if (it->second.canonical != canonical)
    throw InputError({source.string()}, "",
                     "would go to " + in_pack.generic_string() + " in the pack, where " +
                         it->second.source.string() + " goes",
                     std::string("the pack keeps installed catalogue presets in ") + kPackCatalogueFolder +
                         "/: rename the preset folder's own " + kPackCatalogueFolder + "/");
  if (role == "preset" || (role == "base" && it->second.role != "preset")) it->second.role = role;
}

// `preset` as given, so that messages name it as the user did.
void PackPlan::addPreset(const fs::path& preset) {
  loadPreset(preset);  // a preset that does not load is not packed: the same message a bake gives
  const PresetFiles files = presetFiles(preset);
  std::map<fs::path, std::pair<fs::path, Root>> placed;  // chain file → (its path in the pack, its root)
  const fs::path name = files.chain.front().filename();
  if (name == kPackManifestFile)
    throw InputError({preset.string()}, "", "a preset may not be called pack.json in a pack", "rename it");
  placed[files.chain.front()] = {name, Root::Preset};
  add(name, files.chain.front(), "preset", "");
  for (const PresetFileRef& ref : files.refs) {
    const auto& [from_in_pack, from_root] = placed.at(ref.from);
    const Root root = ref.catalogue ? Root::Catalogue : from_root;
    const fs::path to = inPack(ref, root);
    if (to == kPackManifestFile)
      throw InputError(ref.where, ref.key_path, "names a file called pack.json, the pack's own list",
                       "rename the file");
    const bool is_base = ref.key_path == "extends";
    if (is_base) placed[ref.target] = {to, root};
    const std::string catalogue =
        root == Root::Catalogue ? std::string(kCataloguePrefix) + to.lexically_relative(kPackCatalogueFolder).generic_string()
                                : "";
    add(to, ref.target, is_base ? "base" : ref.key_path, catalogue);
    // The value, relative to the naming file's place in the pack.
    const std::string relative = ("/p" / to).lexically_relative(("/p" / from_in_pack).parent_path()).generic_string();
    if (!ref.catalogue && fs::path(ref.written).lexically_normal().generic_string() == relative) continue;
    entries_.at(from_in_pack).edits[ref.offset] = {ref.offset, ref.written, yamlScalar(relative), ref.where,
                                                   ref.key_path};
  }
}

// The bytes of `entry` as the pack holds them: its edits applied.
std::string editedBytes(const PackEntry& entry) {
  std::string text = readBytes(entry.source);
  // yaml-cpp's offsets leave out a UTF-8 byte order mark.
  const std::size_t bom = text.rfind("\xEF\xBB\xBF", 0) == 0 ? 3 : 0;
  for (auto it = entry.edits.rbegin(); it != entry.edits.rend(); ++it) {
    Edit edit = it->second;
    if (!scalarLength(text, edit.offset, edit.written)) edit.offset += bom;
    const auto length = scalarLength(text, edit.offset, edit.written);
    if (!length)
      throw InputError(edit.where, edit.key_path, "cannot rewrite '" + edit.written + "' to name the pack's copy",
                       "write the value on one line");
    text.replace(edit.offset, *length, edit.replacement);
  }
  return text;
}

// ---- the target folder ----

bool isPackManifest(const fs::path& file) {
  try {
    std::ifstream in(file);
    const auto manifest = nlohmann::json::parse(in);
    return manifest.is_object() && manifest.contains("rockbake_pack");
  } catch (const std::exception&) {
    return false;
  }
}

// What `out` is; InputError when it may not be written.
enum class PackTarget { Absent, EmptyFolder, Pack };
PackTarget checkPackTarget(const fs::path& out) {
  const std::string hint =
      "rockbake preset pack writes a new folder or replaces a pack it wrote: give -o a new folder, or move this one "
      "away";
  std::error_code ec;
  const fs::file_status status = fs::symlink_status(out, ec);
  if (status.type() == fs::file_type::not_found) return PackTarget::Absent;
  if (fs::is_symlink(status)) throw InputError({out.string()}, "", "is a symbolic link, not a pack", hint);
  if (!fs::is_directory(status)) throw InputError({out.string()}, "", "is a file, not a pack folder", hint);
  if (fs::is_empty(out, ec)) return PackTarget::EmptyFolder;
  const fs::path manifest = out / kPackManifestFile;
  if (!fs::is_regular_file(fs::symlink_status(manifest, ec)))
    throw InputError({out.string()}, "", "is a folder that is not a pack (it holds no pack.json)", hint);
  if (!isPackManifest(manifest))
    throw InputError({manifest.string()}, "", "is not a rockbake pack's pack.json, so the folder is not a pack", hint);
  return PackTarget::Pack;
}

// Creates `dir`'s missing folders; returns those it made, deepest last.
std::vector<fs::path> makeFolders(const fs::path& dir) {
  std::vector<fs::path> made;
  for (fs::path p = dir; !p.empty() && !fs::exists(p); p = p.parent_path()) made.insert(made.begin(), p);
  fs::create_directories(dir);
  return made;
}

// ".<name><what><pid>": a hidden name beside `dir` for this process.
std::string hiddenSibling(const fs::path& dir, const char* what) {
  std::string name(1, '.');
  name.append(dir.filename().string()).append(what).append(std::to_string(::getpid()));
  return name;
}

// Removes what packs into `dir` that were killed left beside it: hidden folders of processes that are gone.
void removeLeftovers(const fs::path& dir) {
  std::error_code ec;
  std::string stem(1, '.');
  stem += dir.filename().string();
  for (const auto& entry : fs::directory_iterator(dir.parent_path(), ec)) {
    const std::string name = entry.path().filename().string();
    for (const char* what : {".packing-", ".replaced-"}) {
      if (name.rfind(stem + what, 0) != 0) continue;
      const std::string pid = name.substr(stem.size() + std::strlen(what));
      if (pid.empty() || pid.size() > 9 || !std::all_of(pid.begin(), pid.end(), [](char c) { return c >= '0' && c <= '9'; })) continue;
      if (::kill(::pid_t(std::stol(pid)), 0) != 0 && errno == ESRCH) fs::remove_all(entry.path(), ec);
    }
  }
}

// `staging` put in place as `out`, in one step; what `out` held goes.
void commitPack(const fs::path& staging, const fs::path& out, bool replace) {
  if (!replace) {
    fs::rename(staging, out);
    return;
  }
  if (::renameat2(AT_FDCWD, staging.c_str(), AT_FDCWD, out.c_str(), RENAME_EXCHANGE) == 0) {
    fs::remove_all(staging);  // the previous pack, now under the hidden name
    return;
  }
  // No exchange on this filesystem (NFS): the previous pack aside, then the new one in place.
  const fs::path aside = out.parent_path() / hiddenSibling(out, ".replaced-");
  fs::rename(out, aside);
  fs::rename(staging, out);
  fs::remove_all(aside);
}

ordered_json fileJson(const fs::path& in_pack, const PackEntry& entry, const fs::path& written) {
  ordered_json file = {{"path", in_pack.generic_string()},
                       {"size", fs::file_size(written)},
                       {"sha256", sha256File(written)},
                       {"role", entry.role}};
  if (!entry.catalogue.empty()) file["catalogue"] = entry.catalogue;
  return file;
}

// Writes the plan's files and pack.json into `staging`; checks that every preset loads from there.
PackSummary writePack(const PackPlan& plan, const std::vector<std::string>& presets, const fs::path& staging) {
  PackSummary summary;
  ordered_json files = ordered_json::array();
  for (const auto& [in_pack, entry] : plan.entries()) {
    const fs::path written = staging / in_pack;
    fs::create_directories(written.parent_path());
    if (entry.edits.empty()) {
      fs::copy_file(entry.source, written);
    } else {
      writeFileAtomically(written, editedBytes(entry));
      summary.rewritten += entry.edits.size();
    }
    files.push_back(fileJson(in_pack, entry, written));
    summary.bytes += files.back()["size"].get<std::uintmax_t>();
  }
  ordered_json manifest;
  manifest["rockbake_pack"] = kPackFormat;
  manifest["rockbake_version"] = ROCKBAKE_VERSION;
  manifest["presets"] = presets;
  manifest["files"] = std::move(files);
  writeFileAtomically(staging / kPackManifestFile, manifest.dump(2) + "\n");
  for (const auto& preset : presets) try {
      loadPreset(staging / preset);
    } catch (const InputError& e) {
      throw std::runtime_error(std::string("the pack's copy of ") + preset + " does not load: " + e.what());
    }
  summary.presets = presets;
  summary.files = plan.entries().size();
  return summary;
}

}  // namespace

PackSummary packPresets(const std::vector<fs::path>& presets, const fs::path& out_dir) {
  if (presets.empty()) throw InputError({"<command line>"}, "", "no preset to pack", "rockbake preset pack PRESET -o DIR");
  fs::path out = fs::absolute(out_dir).lexically_normal();
  if (!out.has_filename()) out = out.parent_path();
  if (out == out.root_path()) throw InputError({out_dir.string()}, "", "is not a folder a pack can be written to");
  const PackTarget target = checkPackTarget(out);

  const fs::path folder = fs::absolute(presets.front()).lexically_normal().parent_path();
  PackPlan plan(folder);
  std::vector<std::string> names;
  for (const auto& preset : presets) {
    const fs::path file = fs::absolute(preset).lexically_normal();
    if (file.parent_path() != folder)
      throw InputError({preset.string()}, "", "is not in " + folder.string() + ", the folder of the first preset",
                       "a pack holds presets of one folder: pack each folder on its own");
    if (std::find(names.begin(), names.end(), file.filename().string()) != names.end()) continue;
    plan.addPreset(preset);
    names.push_back(file.filename().string());
  }

  const std::vector<fs::path> made = makeFolders(out.parent_path());
  const fs::path staging = out.parent_path() / hiddenSibling(out, ".packing-");
  try {
    removeLeftovers(out);
    fs::remove_all(staging);
    fs::create_directory(staging);
    PackSummary summary = writePack(plan, names, staging);
    if (checkPackTarget(out) != target)  // another process wrote it meanwhile
      throw InputError({out.string()}, "", "changed while the pack was being made", "pack again");
    commitPack(staging, out, target != PackTarget::Absent);
    summary.dir = out;
    summary.replaced = target == PackTarget::Pack;
    return summary;
  } catch (...) {
    std::error_code ec;
    fs::remove_all(staging, ec);
    for (auto it = made.rbegin(); it != made.rend(); ++it) fs::remove(*it, ec);  // only while empty
    throw;
  }
}

bool isPackFolder(const fs::path& dir) {
  std::error_code ec;
  return fs::is_directory(dir, ec) && fs::exists(fs::symlink_status(dir / kPackManifestFile, ec));
}

}  // namespace rockbake
