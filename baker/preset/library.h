// Library files (docs/libraries.md): presets × seeds × wedges, expanded into an ordered
// list of bake jobs, and split into shards.
//
// A library file is a YAML list of entries:
//
//   - preset: presets/goblin.yaml      # relative to the library file (required)
//     name: goblin                     # optional; default: the preset file's stem
//     seeds: [1, 2, 3]                 # or {from: 1, count: 3}; default: the preset's own seed
//     wedges:                          # optional variations, overrides by key path
//       - {name: tall, set: {grid.size: [4, 4, 8], time: 2.0}}
//       - {name: soft, set: {colluvium.yield: 0.8}}
//
// Jobs come in file order: for each entry, for each seed, for each wedge. A
// job's name (its asset folder) is `<name>-<wedge>-s<seed>`; without wedges
// `<name>-s<seed>`, without seeds `<name>-<wedge>`, with neither `<name>`.
// Names use only a-z, 0-9, '_' and '-', so they are safe as folder names.
//
// Every problem throws InputError with the library file, line, column and key
// path ("0.wedges.1.set"); unknown keys get a "did you mean". The preset files
// must exist; whether they are valid is each job's own business.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace rockbake {

struct LibraryWedge {
  std::string name;
  // Overrides in PresetOverrides::sets form ("key.path=<value as YAML flow text>"),
  // in file order, and parallel to them where each was written
  // ("lib.yaml:12:9 (wedge 'tall')").
  std::vector<std::string> sets;
  std::vector<std::string> set_origins;
};

struct LibraryEntry {
  std::string preset;                 // as written, relative to the library file's folder
  std::filesystem::path preset_file;  // resolved against the library file's folder
  std::string name;                   // job name stem
  std::vector<std::uint64_t> seeds;   // empty: the preset's own seed
  std::vector<LibraryWedge> wedges;   // empty: no wedge
};

struct Library {
  std::filesystem::path file;  // as given
  std::string sha256;          // of the file's bytes
  std::vector<LibraryEntry> entries;
};

struct LibraryJob {
  std::string name;                   // the asset folder's name
  std::size_t entry = 0;              // index into Library::entries
  std::optional<std::uint64_t> seed;  // empty: the preset's own seed
  std::optional<LibraryWedge> wedge;
};

Library loadLibrary(const std::filesystem::path& file);
// Same, from text in memory; `file` names it in messages and anchors preset paths.
Library parseLibrary(const std::string& yaml_text, const std::filesystem::path& file);

// Every job of the library in order. Two jobs with one name are an InputError
// located at the second entry.
std::vector<LibraryJob> expandLibrary(const Library& library);

// `--shard I/N`: 0 <= I < N. Throws InputError for anything else.
struct Shard {
  int index = 0;
  int count = 1;
};
Shard parseShard(const std::string& text);
// Round-robin: jobs i with i % count == index, in order. The shards 0..N-1
// together hold every job exactly once.
std::vector<LibraryJob> selectShard(const std::vector<LibraryJob>& jobs, const Shard& shard);

}  // namespace rockbake
