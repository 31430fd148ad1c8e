// The studio's model (docs/studio.md): one preset simulated at a
// preview resolution, cycle by cycle, with edits that become keyframes, a
// timeline of in-memory checkpoints (bounded: studio/checkpoint_timeline.h),
// save, and the state the page shows. No HTTP here (studio/studio_routes.h
// serves it); not thread-safe: the server calls it under one lock.
//
// The contract: save() writes a preset that `rockbake bake --no-mesh
// --resolution <resolution>` turns into a rock.vdb byte-identical to
// rockVdb() at that moment. It holds because the studio's simulation is the
// bake's WeatheringSimulation on the same SimParams, edits only ever change
// keyframes the simulation has not reached yet (or the base graph at time 0,
// which restarts it), and a restored checkpoint is the simulation's own
// snapshot.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "inputs/resolve_shape.h"
#include "preset/load_preset.h"
#include "preset/preset.h"
#include "sim/weathering.h"
#include "studio/checkpoint_timeline.h"

namespace rockbake {

// A request the studio refuses (HTTP 4xx, or 503 when memory ran out): `status`
// and a message that says what to do.
class StudioError : public std::runtime_error {
 public:
  // Control bytes in `message` (it may quote the request) are written as \xNN, so what() holds all of it.
  StudioError(int status, const std::string& message)
      : std::runtime_error(escapeControlBytes(message)), status_(status) {}
  int status() const { return status_; }

 private:
  int status_;
};

struct SaveResult {
  std::filesystem::path path;
  double time = 0.0;
  std::string preset_hash;
};

class StudioSession {
 public:
  // Reads the preset with grid.resolution = `resolution` (InputError on a bad
  // preset, or on a file that is not a regular one of at most 1 MiB: a FIFO or
  // a device is refused before it is read, as `rockbake lint` refuses it).
  StudioSession(const std::filesystem::path& preset_file, int resolution, CheckpointBounds checkpoint_bounds = {});
  ~StudioSession();

  // One cycle (a no-op at the simulation's hard end). Out of memory, the
  // simulation goes back to its latest checkpoint (a cycle cut short may have
  // left it half-done) and StudioError 503 says so; the session carries on.
  CycleStats step();
  // Whether a save keeps the preset's own `time` or `cycles`: the current cycle is the
  // preset's last (otherwise a save writes `time` as the current time).
  bool keepsOwnStop() const;
  bool atEnd() const;          // the preset's time reached, or its `until`: where play stops
  bool finished() const;       // nothing more can run (`until` reached)
  void reset();                // back to time 0, keeping the edits; only time 0's checkpoint stays
  void runUntil(double time);  // forward, or seek back first; rounds up to a whole cycle
  void seek(double time);      // restore the nearest checkpoint at or before, re-simulate to it
  // Out of memory while the simulation was being restored from a checkpoint,
  // the session has none until this rebuilds it (each request starts with it;
  // step, reset and seek call it too). Meanwhile the rest throw StudioError 503.
  void recover();

  // A partial preset: any of durability {points, noise}, bubbles, response.
  // Validated like a preset (StudioError 400 with the reader's message).
  void edit(const nlohmann::json& part);

  SaveResult save(const std::string& name, bool overwrite);
  // The preset as Save would write it (keyframes, time = now), at its own resolution: what bake final bakes.
  Preset finalPreset() const;
  const ResolvedShape& shape() const { return shape_; }

  nlohmann::json state() const;
  // rock.vdb bytes, as `bake --no-mesh` writes them, and the preview mesh
  // (pipeline/preview_mesh.h) in docs/studio.md's binary format. Both run OpenVDB,
  // which cannot recover from running out of memory part-way: StudioError 503
  // first when this process has less memory left than they may need.
  std::string rockVdb() const;
  std::string previewMesh(Palette palette) const;

  int cycle() const;
  double time() const;
  double h() const;
  int resolution() const { return resolution_; }
  std::uint64_t rockVersion() const { return rock_version_; }
  const Preset& preset() const { return preset_; }

 private:
  void restart();  // a new simulation from the initial rock, checkpoints and history cleared
  void restore(const SimulationSnapshot& checkpoint);
  const WeatheringSimulation& simulation() const;        // StudioError 503 while it is lost (recover())
  void requireMemoryFor(const std::string& what) const;  // StudioError 503 below estimatePreviewBytes
  int checkpointSpacing() const;  // the timeline's first spacing: about kCheckpointsPerRun over the preset's time
  SimParams simParams() const;
  // Adds an edit request's keys to `overrides`; returns their key paths (StudioError 400 for others).
  std::vector<std::string> editOverrides(const nlohmann::json& part, PresetOverrides& overrides) const;
  int cycleAt(double time) const;  // the whole cycle a time rounds up to
  std::string savedYaml(const std::string& name) const;

  std::filesystem::path file_;
  std::string original_text_;
  int resolution_;
  int own_resolution_;
  Preset preset_;  // at the studio's resolution, with every edit
  ResolvedShape shape_;
  std::unique_ptr<WeatheringSimulation> sim_;  // empty only while lost: see recover()
  int lost_at_ = -1;                           // then, the cycle it was being restored to
  CheckpointTimeline checkpoints_;
  struct HistoryEntry {
    double time;
    std::size_t rock, exposed, colluvium;
  };
  std::vector<HistoryEntry> history_;  // per cycle run on this branch
  std::size_t initial_rock_ = 0;
  int end_cycle_ = 1;               // the preset's time (or cycles) at the studio's voxel size
  std::uint64_t rock_version_ = 0;  // changes whenever the rock does (the page refetches the mesh)
};

}  // namespace rockbake
