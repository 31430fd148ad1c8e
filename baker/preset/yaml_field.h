// Typed, located reads of YAML for the preset and library readers (docs/libraries.md).
//
// A Field is a YAML node with its key path ("bubbles.0.bubble.sphere.radius")
// and the file and position it came from, so every problem it reports says
// where: file:line:column and key path. Reads record the keys they ask for;
// once a document has been read, reportUnreadKeys() reports every key of a
// checked map that no read asked for as unknown, with a "did you mean". The
// preset's reads are driven by its schema's table (preset/schema_spec.h), so
// the table is the one list of its keys; a library file's are its reader's.
//
// Internal to the preset stage: it exposes yaml-cpp.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "core/did_you_mean.h"
#include "core/error.h"
#include "core/vec3.h"
#include "preset/yaml_text.h"

namespace rockbake {

// ---- where values came from ----

// The file that wrote the values under a key path. With `extends`, a merged
// preset mixes files: yaml-cpp marks carry line and column but not the file.
struct Origin {
  std::string key_path;          // "" = the whole document
  std::string file;              // as named in messages
  std::filesystem::path folder;  // absolute; relative paths in these values resolve against it
};

inline bool underKeyPath(const std::string& path, const std::string& prefix) {
  return prefix.empty() || path == prefix || path.rfind(prefix + ".", 0) == 0;
}

// The origin with the longest key path that `path` lies under. origins.front() is the document's.
inline const Origin& originOf(const std::vector<Origin>& origins, const std::string& path) {
  const Origin* best = &origins.front();
  for (const auto& origin : origins)
    if (underKeyPath(path, origin.key_path) && origin.key_path.size() > best->key_path.size()) best = &origin;
  return *best;
}

// Which keys the reads asked for, so that the keys nobody asked for can be
// reported as unknown afterwards (reportUnreadKeys), with no separate list of
// keys to keep in step with the reading.
struct ReadLog {
  std::set<std::string> asked;              // key paths any read asked for (present or not)
  std::vector<std::string> asked_in_order;  // the same, in the order first asked
  struct CheckedMap {
    std::string path;
    YAML::Node node;
    YAML::Mark mark;
  };
  std::vector<CheckedMap> maps;     // maps whose keys are checked, in the order first read
  std::vector<std::string> failed;  // key paths whose reading stopped at a problem
};

struct Source {
  std::vector<Origin> origins;  // front(): the preset itself, key path ""
  // Key paths replaced on the command line, with what to name as their location
  // ("--set a.b=1", "--seed 7", or a library's "lib.yaml:12:9 (wedge 'tall')").
  std::vector<std::pair<std::string, std::string>> overrides;
  // Linting: problems are recorded here and validation goes on; null: the first one throws.
  std::vector<InputError>* problems = nullptr;
  // Where every key read was written (Preset::locations), when set.
  std::map<std::string, SourceLocation>* locations = nullptr;
  ReadLog* reads = nullptr;  // when set, reads are logged and maps' keys checked afterwards

  const std::string& file() const { return origins.front().file; }
  const std::filesystem::path& folder() const { return origins.front().folder; }
};

// The largest length (and coordinate) a preset may give, in world units. Beyond it products of lengths
// overflow long before a grid could resolve them.
constexpr double kMaxWorldLength = 1e6;
// The most cycles a bake may run, whether given as `cycles` or as `time`.
constexpr long long kMaxCycles = 1000000;

inline std::string formatNumber(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

// A node of the preset with its key path: typed, checked reads.
class Field {
 public:
  Field(YAML::Node node, std::string path, const Source& source, YAML::Mark parent_mark = YAML::Mark::null_mark())
      : node_(std::move(node)), path_(std::move(path)), source_(&source), parent_mark_(parent_mark) {}

  const std::string& path() const { return path_; }
  const YAML::Node& yaml() const { return node_; }
  bool defined() const { return node_.IsDefined() && !node_.IsNull(); }
  bool isMap() const { return node_.IsMap(); }
  bool isSequence() const { return node_.IsSequence(); }

  [[noreturn]] void fail(const std::string& problem, const std::string& hint = {}) const {
    throw InputError(location(), path_, problem, hint);
  }

  // The folder a relative path in this value resolves against: that of the file that wrote it (a base
  // preset's own folder), or the preset's for a value given on the command line.
  std::filesystem::path folder() const {
    return overriddenBy() ? source_->folder() : originOf(source_->origins, path_).folder;
  }
  std::string relativePathHint() const {
    if (overriddenBy()) return "paths given on the command line are relative to the preset's folder";
    const Origin& origin = originOf(source_->origins, path_);
    if (&origin == &source_->origins.front()) return "paths are relative to the preset's folder";
    return "paths are relative to the folder of " + origin.file + ", the file that gives them";
  }

  Field at(const std::string& key) const {
    ask(key);
    // A key the map lacks reads as nothing (null), never as yaml-cpp's invalid node.
    Field field(node_.IsMap() && node_[key].IsDefined() ? node_[key] : YAML::Node(), join(key), *source_,
                markOrParent());
    if (source_->locations && field.defined()) source_->locations->emplace(field.path(), field.location());
    return field;
  }
  bool has(const std::string& key) const {
    ask(key);
    return node_.IsMap() && node_[key].IsDefined() && !node_[key].IsNull();
  }
  // The value of a key that must be given. A key written with no value is reported at the key (an
  // empty value's own position is the start of the next line).
  Field require(const std::string& key, const std::string& problem, const std::string& hint = {}) const {
    if (has(key)) return at(key);
    if (node_.IsMap())
      for (const auto& entry : node_) {
        if (!entry.first.IsScalar()) continue;
        const std::string given = entry.first.Scalar();
        if (given == key) Field(entry.first, join(key), *source_, markOrParent()).fail(problem, hint);
        // A reader that stops at the first problem (no problems list) never gets to report unread
        // keys: a misspelling of the missing key, among the keys not asked for so far, reads best as that.
        const bool asked = source_->reads && source_->reads->asked.count(join(given));
        if (!source_->problems && !asked && closestName(given, {key}))
          Field(entry.first, join(given), *source_, markOrParent())
              .fail("unknown key '" + given + "'; did you mean '" + key + "'?", problem);
      }
    fail(problem, hint);
  }

  // Requires a map with no key given twice. Its keys are checked once reading is done
  // (reportUnreadKeys): a key no read asked for is unknown.
  void expectMap() const {
    for (const Field& key : keys()) (void)key;
    if (source_->reads && std::none_of(source_->reads->maps.begin(), source_->reads->maps.end(),
                                       [&](const ReadLog::CheckedMap& m) { return m.path == path_; }))
      source_->reads->maps.push_back({path_, node_, markOrParent()});
  }

  // A map's keys as fields (located at the key), in order; a key given twice or one
  // that is not a name is an error. For maps whose keys are data (a wedge's `set:`
  // key paths): every key counts as asked for.
  std::vector<Field> keys() const {
    if (!node_.IsMap()) fail("expected a map (key: value, ...), found " + describe(node_));
    std::vector<Field> seen;
    for (const auto& entry : node_) {
      if (!entry.first.IsScalar())
        Field(entry.first, path_, *source_, markOrParent()).fail("expected a key name, found " + describe(entry.first));
      const std::string key = entry.first.Scalar();
      // yaml-cpp keeps both entries of a repeated key and lookups find the first: an edit further down
      // the file would be silently ignored.
      for (const Field& s : seen)
        if (s.node_.Scalar() == key)
          Field(entry.first, join(key), *source_, markOrParent())
              .fail("'" + key + "' is given twice (first on line " + std::to_string(s.node_.Mark().line + 1) + ")",
                    "keep one of them");
      seen.push_back(Field(entry.first, join(key), *source_, markOrParent()));
    }
    return seen;
  }
  // keys(), each one counted as asked for.
  std::vector<Field> dataKeys() const {
    std::vector<Field> all = keys();
    for (const Field& key : all) ask(key.node_.Scalar());
    return all;
  }

  // Exactly one of `kinds` must be present; returns it. Other keys may stand beside it
  // when something reads them.
  std::string oneOf(const std::vector<std::string>& kinds) const {
    expectMap();
    std::vector<std::string> present;
    for (const auto& k : kinds)
      if (ask(k), node_[k].IsDefined()) present.push_back(k);
    if (present.empty())  // a misspelled kind reads best as that
      for (const Field& key : keys())
        if (const auto best = closestName(key.node_.Scalar(), kinds))
          key.fail("unknown key '" + key.node_.Scalar() + "'; did you mean '" + *best + "'?",
                   "give exactly one of: " + joinNames(kinds));
    if (present.size() != 1)
      fail(present.empty() ? "needs one of: " + joinNames(kinds)
                           : "has " + joinNames(present) + "; give exactly one of: " + joinNames(kinds));
    return present.front();
  }

  std::size_t size() const {
    if (!node_.IsSequence()) fail("expected a list, found " + describe(node_));
    return node_.size();
  }
  Field item(std::size_t i) const { return Field(node_[i], join(std::to_string(i)), *source_, markOrParent()); }

  double number() const {
    if (!node_.IsScalar()) fail("expected a number, found " + describe(node_));
    try {
      const double v = node_.as<double>();
      if (!std::isfinite(v)) fail("expected a finite number, found " + describe(node_));
      return v;
    } catch (const YAML::Exception&) {
      fail("expected a number, found " + describe(node_));
    }
  }
  double numberIn(double lo, double hi, bool lo_open = false, bool hi_open = false) const {
    const double v = number();
    if ((lo_open ? v <= lo : v < lo) || (hi_open ? v >= hi : v > hi))
      fail("must be in " + std::string(lo_open ? "(" : "[") + formatNumber(lo) + ", " + formatNumber(hi) +
           (hi_open ? ")" : "]") + ", found " + formatNumber(v));
    return v;
  }
  double positive() const {
    const double v = number();
    if (v <= 0) fail("must be greater than 0, found " + formatNumber(v));
    return v;
  }
  // A length in world units: > 0 and at most kMaxWorldLength.
  double length() const {
    const double v = positive();
    if (v > kMaxWorldLength)
      fail("must be at most " + formatNumber(kMaxWorldLength) + " world units, found " + formatNumber(v));
    return v;
  }
  long long integer(long long lo, long long hi) const {
    if (!node_.IsScalar()) fail("expected a whole number, found " + describe(node_));
    long long v = 0;
    try {
      v = node_.as<long long>();
    } catch (const YAML::Exception&) {
      fail("expected a whole number, found " + describe(node_));
    }
    if (v < lo || v > hi)
      fail("must be a whole number from " + std::to_string(lo) + " to " + std::to_string(hi) + ", found " +
           std::to_string(v));
    return v;
  }
  std::uint64_t unsigned64() const {
    if (const auto value = unsignedValue(node_)) return *value;
    fail("expected a whole number >= 0, found " + describe(node_));
  }
  bool boolean() const {
    if (!node_.IsScalar()) fail("expected true or false, found " + describe(node_));
    try {
      return node_.as<bool>();
    } catch (const YAML::Exception&) {
      fail("expected true or false, found " + describe(node_));
    }
  }
  std::string string() const {
    if (!node_.IsScalar()) fail("expected text, found " + describe(node_));
    return node_.Scalar();
  }
  std::string choice(const std::vector<std::string>& options) const {
    const std::string v = string();
    if (std::find(options.begin(), options.end(), v) == options.end())
      fail("'" + v + "' is not one of: " + joinNames(options));
    return v;
  }
  // Three lengths (sizes, radii, half extents).
  Vec3d positiveVec3() const {
    if (size() != 3) fail("expected a list of 3 numbers, found " + std::to_string(size()));
    return {item(0).length(), item(1).length(), item(2).length()};
  }
  // A position: each coordinate within ±kMaxWorldLength.
  Vec3d vec3() const {
    if (size() != 3) fail("expected a list of 3 numbers, found " + std::to_string(size()));
    return {item(0).numberIn(-kMaxWorldLength, kMaxWorldLength), item(1).numberIn(-kMaxWorldLength, kMaxWorldLength),
            item(2).numberIn(-kMaxWorldLength, kMaxWorldLength)};
  }

  // Where this value was written: file:line:column, or the command-line flag that set it.
  SourceLocation location() const {
    if (const std::string* argument = overriddenBy()) return {*argument, 0, 0};
    const std::string& file = originOf(source_->origins, path_).file;
    const YAML::Mark mark = markOrParent();
    if (mark.is_null()) return {file, 0, 0};
    return {file, mark.line + 1, mark.column + 1};
  }

 private:
  void ask(const std::string& key) const {
    if (source_->reads && source_->reads->asked.insert(join(key)).second)
      source_->reads->asked_in_order.push_back(join(key));
  }
  std::string join(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }
  YAML::Mark markOrParent() const {
    return (node_.IsDefined() && !node_.Mark().is_null()) ? node_.Mark() : parent_mark_;
  }
  // A value that came from --set is located there, not in the file; so is a key the flag created on
  // its way ("colluvum" in --set colluvum.yield=0.3), which has no position. The last flag wins.
  const std::string* overriddenBy() const {
    const bool from_file = node_.IsDefined() && !node_.Mark().is_null();
    for (auto it = source_->overrides.rbegin(); it != source_->overrides.rend(); ++it) {
      const auto& [path, argument] = *it;
      if (underKeyPath(path_, path)) return &argument;
      if (!from_file && !path_.empty() && path.rfind(path_ + ".", 0) == 0) return &argument;
    }
    return nullptr;
  }

  YAML::Node node_;
  std::string path_;
  const Source* source_;
  YAML::Mark parent_mark_;
};

// Every key of the checked maps that no read asked for, as "unknown key"
// problems located at the key, with the closest asked-for key as a suggestion.
// Maps whose reading stopped at a problem are left out: their later keys were
// never asked for. Sorted in reading order.
std::vector<InputError> unreadKeyProblems(const Source& source);

}  // namespace rockbake
