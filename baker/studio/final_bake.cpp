#include "studio/final_bake.h"

#include <fmt/format.h>

#include "pipeline/bake_asset.h"
#include "studio/studio_session.h"

namespace rockbake {

FinalBake::~FinalBake() {
  cancel_ = true;
  if (thread_.joinable()) thread_.join();
}

std::filesystem::path FinalBake::start(Preset preset, ResolvedShape shape) {
  std::lock_guard lock(mutex_);
  if (status_.state == "running") throw StudioError(409, "a final bake is already running");
  if (thread_.joinable()) thread_.join();  // the last one, finished
  const std::filesystem::path asset_dir = out_dir_ / preset.name;
  status_ = {"running", 0.0, "starting", asset_dir.string()};
  cancel_ = false;
  thread_ = std::thread([this, preset = std::move(preset), shape = std::move(shape)] { bake(preset, shape); });
  return asset_dir;
}

BakeStatus FinalBake::status() const {
  std::lock_guard lock(mutex_);
  return status_;
}

void FinalBake::bake(const Preset& preset, const ResolvedShape& shape) {
  BakeOptions options;
  options.out_dir = out_dir_;
  options.cancel = &cancel_;
  options.progress = [this](double fraction, const std::string& stage) {
    std::lock_guard lock(mutex_);
    status_.progress = fraction;
    status_.message = stage;
  };
  bool done = false;
  std::string message;
  try {
    const BakeSummary summary = bakeAsset(preset, shape, options);
    done = true;
    message = fmt::format("{} cycles in {:.1f} s → {}", summary.cycles, summary.seconds, summary.asset_dir.string());
  } catch (const std::exception& e) {
    try {
      message = e.what();
    } catch (const std::bad_alloc&) {
    }
  }
  std::lock_guard lock(mutex_);
  status_.state = done ? "done" : "failed";  // both fit in the string's own buffer
  status_.message.swap(message);
  if (done) status_.progress = 1.0;
}

}  // namespace rockbake
