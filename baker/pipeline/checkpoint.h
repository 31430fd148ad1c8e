// Checkpoints (SPEC §5): the whole simulation state at one time, in one file
// (`bake --checkpoint-every T` writes OUT/<name>/checkpoints/<time>.rbk), and
// what `rockbake resume` continues from (pipeline/resume_plan.h).
//
// File layout (little-endian), version 1:
//   "RBKPOINT"  u32 version  u64 header bytes  header (JSON)
//   u64 cells   materials u8[cells]  integrity f32[cells]  durability f32[cells]
//   u64 columns colluvium accumulators i64[columns]
//   SHA-256 of everything before it, 64 hex digits
// The header holds the grid layout, cycle, time, the preset's own text, its
// file and the overrides the bake had, the resolved preset and its hash, and
// the per-cycle statistics so far (stats.json's list).
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

// Throws InputError naming the file when it cannot be read, is not a
// checkpoint, is of another version, is truncated or fails its checksum.
Checkpoint readCheckpoint(const std::filesystem::path& file);

// Same, from the file's bytes in memory; `file` names it in messages.
Checkpoint parseCheckpoint(std::string_view bytes, const std::filesystem::path& file);

}  // namespace rockbake
