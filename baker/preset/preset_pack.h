// Packs: a preset bundled with every file it reaches, to share (docs/libraries.md,
// "Sharing presets"; pack.json in docs/formats.md).
//
// `rockbake preset pack PRESET... -o DIR` copies each preset, the bases it extends
// (kept as files: the extends chain stays) and every file a path key names
// (preset/preset_files.h) into DIR, under their paths relative to the presets' folder;
// installed catalogue presets it extends (`extends: rockbake:NAME`) go to DIR/rockbake/,
// and the `extends` naming them is rewritten to that copy, so the pack needs nothing
// outside itself. DIR/pack.json lists every file with its size and SHA-256. Nothing a
// preset reaches may lie outside its own folder (after symbolic links), save installed
// catalogue presets named as such: a shared preset is untrusted input.
//
// The pack is built in a hidden sibling folder (DIR/../.<name>.packing-<pid>) and put in
// place in one step, so a failure leaves nothing; DIR may be absent, an empty folder or a
// pack (replaced whole), nothing else.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "core/error.h"

namespace rockbake {

inline constexpr const char* kPackManifestFile = "pack.json";
// Where a pack keeps the installed catalogue presets its presets extend.
inline constexpr const char* kPackCatalogueFolder = "rockbake";
inline constexpr int kPackFormat = 1;

struct PackSummary {
  std::filesystem::path dir;
  std::vector<std::string> presets;  // relative to dir
  std::size_t files = 0;             // pack.json not counted
  std::uintmax_t bytes = 0;
  std::size_t rewritten = 0;  // values rewritten to name the pack's copies (installed bases, absolute paths)
  bool replaced = false;      // DIR held a pack, which the new one replaced
};

// Writes the pack, or throws: InputError (exit status 2, nothing written) for a preset that does not
// load, reaches outside its folder or names a missing file, presets in different folders, or a DIR that
// is not a pack; std::runtime_error when a file cannot be written.
PackSummary packPresets(const std::vector<std::filesystem::path>& presets, const std::filesystem::path& out_dir);

// `dir` holds a pack.json: it is meant as a pack (checkPack says whether it is a sound one).
bool isPackFolder(const std::filesystem::path& dir);

struct PackCheck {
  std::vector<std::string> presets;  // as pack.json lists them, relative to the pack
  std::size_t files = 0;
  std::vector<InputError> problems;
};

// The pack's own problems, for `rockbake lint`: pack.json readable and of this format; every file it
// lists present, a plain file (no symbolic link on the way) inside the pack, of its size and SHA-256;
// nothing in the pack it does not list; and every file a listed preset reaches is in the pack and
// listed (no installed catalogue name either: a pack holds its bases). The presets' own problems are
// lintPreset's.
PackCheck checkPack(const std::filesystem::path& dir);

}  // namespace rockbake
