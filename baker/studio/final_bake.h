// The studio's Bake final (docs/studio.md, "POST /api/bake"): the normal bake
// (pipeline/bake_asset.h, with its asset-folder rule and lock) of what the page
// shows, at the preset's own resolution, on a thread of its own, with its
// progress for the page. One at a time; cancelled when the studio stops.
#pragma once

#include <atomic>
#include <filesystem>
#include <mutex>
#include <string>
#include <thread>

#include "inputs/resolve_shape.h"
#include "preset/preset.h"

namespace rockbake {

struct BakeStatus {
  std::string state = "idle";  // idle, running, done, failed
  double progress = 0.0;       // 0..1
  std::string message;         // the stage under way, the summary, or what failed
  std::string asset_dir;
};

class FinalBake {
 public:
  explicit FinalBake(std::filesystem::path out_dir) : out_dir_(std::move(out_dir)) {}
  ~FinalBake();  // cancels a bake under way and waits for it
  FinalBake(const FinalBake&) = delete;
  FinalBake& operator=(const FinalBake&) = delete;

  // Starts baking `preset` into OUT/<name>/ and returns that folder;
  // StudioError 409 while another runs.
  std::filesystem::path start(Preset preset, ResolvedShape shape);
  BakeStatus status() const;
  void cancel() { cancel_ = true; }

 private:
  void bake(const Preset& preset, const ResolvedShape& shape);

  std::filesystem::path out_dir_;
  mutable std::mutex mutex_;  // guards status_
  BakeStatus status_;
  std::atomic<bool> cancel_{false};
  std::thread thread_;
};

}  // namespace rockbake
