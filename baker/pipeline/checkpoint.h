// Checkpoints (docs/libraries.md): the whole simulation state at one time, in one file
// (`bake --checkpoint-every T` writes OUT/<name>/checkpoints/<time>.rbk), and
// what `rockbake resume` continues from (pipeline/resume_plan.h).
//
// File layout (little-endian), version 1:
//   "RBKPOINT"  u32 version  u64 header bytes  header (JSON)
//   u64 cells   materials u8[cells]  integrity, durability: row spans
//   u64 rind cells (0 or cells)  rind u8[rind cells]
//   u64 columns colluvium accumulators i64[columns]
//   SHA-256 of everything before it, 64 hex digits
// Row spans are f32 fill, then per row (y + ny z) i32 first x, u32 count and
// f32[count]. The header holds the grid layout, cycle, time, the preset's own
// text, its file and the overrides the bake had, the resolved preset and its
// hash, and the per-cycle statistics so far (stats.json's list).
#pragma once

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

inline constexpr std::uint32_t kCheckpointVersion = 1;

// `<time>.rbk`, the time to 6 significant digits ("0.75.rbk").
std::string checkpointFileName(double time);

// The file's bytes.
std::string checkpointBytes(const Checkpoint& checkpoint);

// Atomic: a checkpoint being written is never mistaken for a whole one.
void writeCheckpoint(const std::filesystem::path& file, const Checkpoint& checkpoint);

// A checkpoint from its bytes; `file` names it in messages. Throws InputError
// naming `file` when the bytes are not a checkpoint, are of another version,
// are truncated, fail their checksum, or hold a header (at most 64 levels
// deep) or arrays that do not fit together. A checkpoint that reads can start
// a simulation: its layout is a real grid, every array is that grid's size,
// its cycle is not negative. Nothing is allocated for a size the bytes cannot
// hold.
Checkpoint parseCheckpoint(std::string_view bytes, const std::filesystem::path& file);

// Same, from the file; InputError too when it cannot be read or is not a
// regular file.
Checkpoint readCheckpoint(const std::filesystem::path& file);

}  // namespace rockbake
