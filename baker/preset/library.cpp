// Library file parsing: yaml-cpp nodes → plain LibraryEntry data, every read
// located (file:line:column + key path) so every error says where it is.
#include "preset/library.h"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <set>
#include <sstream>
#include <unordered_map>

#include <yaml-cpp/yaml.h>

#include "core/did_you_mean.h"
#include "core/error.h"
#include "core/sha256.h"
#include "preset/yaml_field.h"
#include "preset/yaml_text.h"

namespace rockbake {
namespace {

constexpr std::uint64_t kMaxSeedCount = 100000;
// The most jobs one library may hold: beyond it a typo (a count of 100000 on every entry) would run away.
constexpr std::uint64_t kMaxJobs = 100000;

std::vector<std::uint64_t> readSeeds(const Field& seeds) {
  std::vector<std::uint64_t> out;
  if (seeds.yaml().IsMap()) {
    seeds.expectMap();
    if (!seeds.has("from") || !seeds.has("count"))
      seeds.fail("a seed range needs both 'from' and 'count'", "for example seeds: {from: 1, count: 8}");
    const std::uint64_t from = seeds.at("from").unsigned64();
    const Field count_node = seeds.at("count");
    const std::uint64_t count = count_node.unsigned64();
    if (count < 1 || count > kMaxSeedCount)
      count_node.fail("must be from 1 to " + std::to_string(kMaxSeedCount) + ", found " + std::to_string(count));
    if (from > std::numeric_limits<std::uint64_t>::max() - (count - 1))
      seeds.fail("the range runs past the largest seed (2^64 - 1)");
    for (std::uint64_t i = 0; i < count; ++i) out.push_back(from + i);
    return out;
  }
  if (!seeds.yaml().IsSequence())
    seeds.fail("expected a list of seeds or {from, count}, found " + describe(seeds.yaml()),
               "for example seeds: [1, 2, 3] or seeds: {from: 1, count: 8}");
  if (seeds.size() == 0) seeds.fail("the list of seeds is empty", "leave 'seeds' out to use the preset's own seed");
  for (std::size_t i = 0; i < seeds.size(); ++i) {
    const std::uint64_t seed = seeds.item(i).unsigned64();
    if (std::find(out.begin(), out.end(), seed) != out.end())
      seeds.item(i).fail("seed " + std::to_string(seed) + " is listed twice");
    out.push_back(seed);
  }
  return out;
}

// A YAML value as one line of flow text, the form --set takes.
std::string flowText(const YAML::Node& value) {
  YAML::Emitter out;
  out.SetMapFormat(YAML::Flow);
  out.SetSeqFormat(YAML::Flow);
  out << value;
  return out.c_str();
}

LibraryWedge readWedge(const Field& w, const std::string& file_label) {
  w.expectMap();
  LibraryWedge wedge;
  w.has("set");  // known before 'name' is required, so it is not taken for a misspelling
  const Field name = w.require("name", "a wedge needs a 'name' (it becomes part of the job name)");
  wedge.name = name.string();
  if (const auto problem = assetNameProblem(wedge.name))
    name.fail(*problem, "it becomes part of the asset folder's name");
  if (!w.has("set") || w.at("set").yaml().IsNull()) return wedge;  // a wedge without overrides: the preset as is
  const Field set = w.at("set");
  for (const Field& key : set.dataKeys()) {
    const std::string path = key.yaml().Scalar();
    std::stringstream parts(path);
    bool bad_path = path.empty() || path.back() == '.' || std::any_of(path.begin(), path.end(), [](char c) {
                      return c == '=' || std::isspace(static_cast<unsigned char>(c));
                    });
    for (std::string part; std::getline(parts, part, '.');) bad_path = bad_path || part.empty();
    if (bad_path)
      key.fail("'" + path + "' is not a key path", "write dotted keys like colluvium.yield or bubbles.0.spheroidal");
    wedge.sets.push_back(path + "=" + flowText(set.yaml()[path]));
    const SourceLocation where = key.location();
    wedge.set_origins.push_back(file_label + ":" + std::to_string(where.line) + ":" + std::to_string(where.column) +
                                " (wedge '" + wedge.name + "')");
  }
  return wedge;
}

std::string stemName(const std::filesystem::path& preset) {
  std::string name;
  for (char c : preset.stem().string()) {
    const char lower = (c >= 'A' && c <= 'Z') ? char(c - 'A' + 'a') : c;
    name += isAssetName(std::string(1, lower)) ? lower : '-';
  }
  return name;
}

LibraryEntry readEntry(const Field& e, const std::filesystem::path& base_dir, const std::string& file_label) {
  if (!e.yaml().IsMap())
    e.fail("expected a library entry (a map with 'preset', and optionally 'name', 'seeds', 'wedges'), found " +
           describe(e.yaml()));
  e.expectMap();
  LibraryEntry entry;
  for (const char* key : {"name", "seeds", "wedges"}) e.has(key);  // known before 'preset' is required
  const Field preset = e.require("preset", "an entry needs 'preset' (a preset file, relative to the library file)");
  entry.preset = preset.string();
  entry.preset_file = base_dir / entry.preset;
  std::error_code unreadable;  // e.g. a name too long for the file system: no file, not a crash
  if (entry.preset.empty() || !std::filesystem::is_regular_file(entry.preset_file, unreadable))
    preset.fail("no preset file at " + entry.preset_file.string(), "preset paths are relative to the library file");

  if (e.has("name")) {
    const Field name = e.at("name");
    entry.name = name.string();
    if (const auto problem = assetNameProblem(entry.name)) name.fail(*problem, "it becomes the asset folders' names");
  } else {
    entry.name = stemName(entry.preset_file);
    if (!isAssetName(entry.name)) preset.fail("cannot make a job name from this file name", "give the entry a 'name'");
  }

  if (e.has("seeds")) entry.seeds = readSeeds(e.at("seeds"));

  if (e.has("wedges")) {
    const Field wedges = e.at("wedges");
    if (wedges.size() == 0) wedges.fail("the list of wedges is empty", "leave 'wedges' out to bake the preset as is");
    for (std::size_t i = 0; i < wedges.size(); ++i) {
      LibraryWedge wedge = readWedge(wedges.item(i), file_label);
      for (const auto& other : entry.wedges)
        if (other.name == wedge.name)
          wedges.item(i).at("name").fail("wedge '" + wedge.name + "' is named twice in this entry");
      entry.wedges.push_back(std::move(wedge));
    }
  }
  return entry;
}

std::string jobName(const LibraryEntry& entry, const LibraryWedge* wedge, const std::uint64_t* seed) {
  std::string name = entry.name;
  if (wedge) name += "-" + wedge->name;
  if (seed) name += "-s" + std::to_string(*seed);
  return name;
}

}  // namespace

Library parseLibrary(const std::string& yaml_text, const std::filesystem::path& file) {
  const std::string label = file.string();
  const YAML::Node root_yaml = loadYamlDocument(yaml_text, label, "a library");
  Source source;
  source.origins.push_back({"", label, std::filesystem::absolute(file).parent_path()});
  ReadLog reads;
  source.reads = &reads;
  const Field root(root_yaml, "", source);
  if (!root_yaml.IsSequence() || root_yaml.size() == 0)
    throw InputError({label, 1, 1}, "", "a library must be a non-empty YAML list of entries",
                     "for example:\n- preset: rock.yaml\n  seeds: [1, 2]");

  Library library;
  library.file = file;
  library.sha256 = sha256Hex(yaml_text);
  const std::filesystem::path base_dir = file.parent_path();
  std::uint64_t job_count = 0;
  for (std::size_t i = 0; i < root.size(); ++i) {
    LibraryEntry entry = readEntry(root.item(i), base_dir, label);
    // Counted before anything is expanded.
    job_count += std::max<std::uint64_t>(1, entry.seeds.size()) * std::max<std::uint64_t>(1, entry.wedges.size());
    if (job_count > kMaxJobs)
      root.item(i).fail("the library holds more than " + std::to_string(kMaxJobs) + " jobs with this entry",
                        "split it into several library files");
    library.entries.push_back(std::move(entry));
  }
  if (const std::vector<InputError> unknown = unreadKeyProblems(source); !unknown.empty()) throw unknown.front();

  // Two jobs with one name would bake into one folder: refuse before anything runs.
  std::unordered_map<std::string, std::size_t> names;  // job name → entry
  names.reserve(job_count);
  for (std::size_t i = 0; i < library.entries.size(); ++i)
    for (const auto& job : expandLibrary(Library{{}, {}, {library.entries[i]}})) {
      const auto [clash, added] = names.emplace(job.name, i);
      if (!added)
        root.item(i).fail("job '" + job.name + "' is also made by entry " + std::to_string(clash->second),
                          "every job needs its own asset folder: give one of the entries another 'name'");
    }
  return library;
}

Library loadLibrary(const std::filesystem::path& file) {
  const std::optional<std::string> text = readYamlFile(file.string(), "a library file");
  if (!text) throw InputError({file.string()}, "", "cannot read the library file", "check the path");
  return parseLibrary(*text, file);
}

std::vector<LibraryJob> expandLibrary(const Library& library) {
  std::vector<LibraryJob> jobs;
  for (std::size_t e = 0; e < library.entries.size(); ++e) {
    const LibraryEntry& entry = library.entries[e];
    const std::size_t seed_count = std::max<std::size_t>(1, entry.seeds.size());
    const std::size_t wedge_count = std::max<std::size_t>(1, entry.wedges.size());
    for (std::size_t s = 0; s < seed_count; ++s)
      for (std::size_t w = 0; w < wedge_count; ++w) {
        LibraryJob job;
        job.entry = e;
        if (!entry.seeds.empty()) job.seed = entry.seeds[s];
        if (!entry.wedges.empty()) job.wedge = entry.wedges[w];
        job.name = jobName(entry, job.wedge ? &*job.wedge : nullptr, job.seed ? &*job.seed : nullptr);
        jobs.push_back(std::move(job));
      }
  }
  return jobs;
}

Shard parseShard(const std::string& text) {
  const auto bad = [&](const std::string& problem) -> Shard {
    throw InputError({"--shard"}, "", "'" + text + "': " + problem,
                     "write I/N with 0 <= I < N, for example --shard 0/4 for the first of four shards");
  };
  const std::size_t slash = text.find('/');
  if (slash == std::string::npos) return bad("expected I/N");
  const auto number = [&](const std::string& part) -> long long {
    if (part.empty() || part.size() > 9 ||
        !std::all_of(part.begin(), part.end(), [](char c) { return c >= '0' && c <= '9'; }))
      bad("'" + part + "' is not a whole number");
    return std::stoll(part);
  };
  const long long index = number(text.substr(0, slash)), count = number(text.substr(slash + 1));
  if (count < 1) return bad("N must be at least 1");
  if (index >= count) return bad("I must be less than N (shards are numbered from 0)");
  return {int(index), int(count)};
}

std::vector<LibraryJob> selectShard(const std::vector<LibraryJob>& jobs, const Shard& shard) {
  std::vector<LibraryJob> mine;
  for (std::size_t i = 0; i < jobs.size(); ++i)
    if (i % std::size_t(shard.count) == std::size_t(shard.index)) mine.push_back(jobs[i]);
  return mine;
}

}  // namespace rockbake
