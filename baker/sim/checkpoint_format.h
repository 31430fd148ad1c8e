// The checkpoint format (docs/libraries.md): the whole simulation state at one time as
// bytes, and back. No file I/O: pipeline/checkpoint.h reads and writes the
// files (`bake --checkpoint-every T` writes OUT/<name>/checkpoints/<time>.rbk,
// `rockbake resume` continues one), and the fuzzer (fuzz/fuzz_checkpoint.cpp)
// feeds this reader bytes directly.
//
// Layout (little-endian), version 2:
//   "RBKPOINT"  u32 version  u64 header bytes  header (JSON)
//   u64 cells   materials u8[cells]  integrity, durability: row spans
//   the history (core/voxel_rock.h): exposed, covered, covered_for, scarred: row spans
//   u64 rind cells (0 or cells)  rind u8[rind cells]
//   u64 columns colluvium accumulators i64[columns]
//   SHA-256 of everything before it, 64 hex digits
// Row spans are f32 fill, then per row (y + ny z) i32 first x, u32 count and
// f32[count]. The header holds the grid layout, cycle, time, the preset's own
// text, its file and the overrides the bake had, the resolved preset and its
// hash, and the per-cycle statistics so far (stats.json's list).
//
// Every reader here throws InputError naming `file` (what the messages call
// the bytes) when they are not a checkpoint this rockbake reads.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "preset/load_preset.h"
#include "preset/preset.h"
#include "sim/weathering.h"

namespace rockbake {

struct Checkpoint {
  SimulationSnapshot snapshot;
  std::filesystem::path preset_file;  // absolute; relative paths in the preset resolve against its folder
  std::string preset_text;            // the preset file as the bake read it
  PresetOverrides overrides;          // --set, --seed, --resolution as the bake had them
  nlohmann::json preset;              // presetToJson of the preset baked
  std::string preset_hash;
  nlohmann::ordered_json cycles = nlohmann::ordered_json::array();  // per-cycle statistics up to the checkpoint
};

inline constexpr std::uint32_t kCheckpointVersion = 2;  // 2: the weathering history
// The magic, the version and the header's length: what a reader checks first.
inline constexpr std::size_t kCheckpointPrefixBytes = 8 + 4 + 8;

// `<time>.rbk`, the time to 6 significant digits ("0.75.rbk").
std::string checkpointFileName(double time);

// The checkpoint's bytes.
std::string checkpointBytes(const Checkpoint& checkpoint);

// A checkpoint from its bytes. Refused when they are not a checkpoint, are of
// another version, are truncated, fail their checksum, or hold a header (at
// most 64 levels deep) or arrays that do not fit together. A checkpoint that
// reads can start a simulation: its layout is a real grid, every array is that
// grid's size, its cycle is not negative. Nothing is allocated for a size the
// bytes cannot hold.
Checkpoint parseCheckpoint(std::string_view bytes, const std::filesystem::path& file);

// For a reader of a file of `file_size` bytes, before it reads the rest: the
// header's length, from the file's first kCheckpointPrefixBytes (fewer when the
// file is shorter). Refused when they are not a checkpoint's, of this version,
// or claim a header longer than the file holds.
std::uint64_t checkpointHeaderLength(std::string_view prefix, std::uint64_t file_size,
                                     const std::filesystem::path& file);

// The most bytes a checkpoint with this header (the text after the prefix)
// can have: each span row full. A file larger than that is refused before it
// is read.
std::uint64_t checkpointMostBytes(std::string_view header_text, std::uint64_t file_size,
                                  const std::filesystem::path& file);

}  // namespace rockbake
