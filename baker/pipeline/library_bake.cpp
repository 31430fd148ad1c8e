#include "pipeline/library_bake.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <mutex>
#include <set>
#include <thread>

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <tbb/parallel_pipeline.h>
#include <tbb/task_arena.h>
#include <nlohmann/json.hpp>

#include "pipeline/bake_asset.h"
#include "pipeline/library_index.h"
#include "pipeline/manifest.h"
#include "sim/voxel_rock.h"
#include "util/error.h"

namespace rockbake {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

enum class Status { Baked, Skipped, Failed, NotRun };

struct JobOutcome {
  std::size_t index = 0;
  Status status = Status::NotRun;
  std::string message;
  double seconds = 0;
};

std::string clockText(double seconds) {
  const long s = long(std::lround(std::max(0.0, seconds)));
  return s >= 3600 ? fmt::format("{}:{:02}:{:02}", s / 3600, s / 60 % 60, s % 60)
                   : fmt::format("{}:{:02}", s / 60, s % 60);
}

// Progress and ETA: one status line redrawn in place on a terminal, plain log
// lines otherwise. Called from the pipeline's threads.
class Progress {
 public:
  // Log lines go through a copy of the default logger kept at info level, so they show while the
  // jobs' own logs are turned down.
  Progress(std::size_t total, int jobs, bool terminal, const std::atomic<bool>* cancel)
      : total_(total),
        jobs_(jobs),
        terminal_(terminal),
        cancel_(cancel),
        log_(spdlog::default_logger()->clone("library")) {
    log_->set_level(spdlog::level::info);
    // On a terminal the status line also ticks between events, so elapsed time and ETA stay current.
    if (terminal_)
      ticker_ = std::thread([this] {
        std::unique_lock lock(mutex_);
        while (!stopping_) {
          redraw();
          tick_.wait_for(lock, std::chrono::seconds(1));
        }
      });
  }
  ~Progress() { finish(); }

  void started(const std::string& name) {
    std::lock_guard lock(mutex_);
    running_.insert(name);
    if (terminal_)
      redraw();
    else
      log_->info("{}: started ({} running)", name, running_.size());
  }

  void finished(const std::string& name, const JobOutcome& outcome) {
    std::lock_guard lock(mutex_);
    running_.erase(name);
    ++done_;
    if (outcome.status == Status::Baked) baked_seconds_ += outcome.seconds, ++baked_;
    if (outcome.status == Status::Failed) ++failed_;
    const char* what = outcome.status == Status::Baked     ? "baked"
                       : outcome.status == Status::Skipped ? "complete, skipped (resumed)"
                       : outcome.status == Status::Failed  ? "FAILED"
                                                           : "stopped";
    std::string line = fmt::format("[{}/{}] {}: {} in {:.1f} s", done_, total_, name, what, outcome.seconds);
    if (outcome.status == Status::Failed) line += ": " + outcome.message;
    if (terminal_) {
      // Failures stay on screen; everything else lives in the status line.
      if (outcome.status == Status::Failed) std::fprintf(stderr, "\r\033[K%s\n", line.c_str());
      redraw();
    } else {
      if (outcome.status == Status::Failed)
        log_->error("{}", line);
      else
        log_->info("{} (ETA {})", line, clockText(eta()));
    }
  }

  void finish() {
    {
      std::lock_guard lock(mutex_);
      if (stopping_) return;
      stopping_ = true;
      if (terminal_) std::fprintf(stderr, "\r\033[K"), std::fflush(stderr);
    }
    tick_.notify_all();
    if (ticker_.joinable()) ticker_.join();
  }

 private:
  // Remaining jobs × mean seconds of the jobs baked so far, shared among the parallel jobs.
  double eta() const {
    if (baked_ == 0) return 0;
    const double remaining = double(total_ - done_);
    return remaining * (baked_seconds_ / baked_) / std::max(1.0, std::min<double>(jobs_, remaining));
  }

  void redraw() {
    const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
    std::string running;
    for (const auto& name : running_) running += (running.empty() ? "" : ", ") + name;
    const bool stopping = cancel_ && cancel_->load();
    std::string line = fmt::format("{}[{}/{}] {} failed, elapsed {}, ETA {}{}{}",
                                   stopping ? "stopping at the next stage (Ctrl-C again: at once) " : "", done_, total_,
                                   failed_, clockText(elapsed), baked_ ? clockText(eta()) : std::string("--:--"),
                                   running.empty() ? "" : " | ", running);
    if (line.size() > 150) line = line.substr(0, 147) + "...";
    std::fprintf(stderr, "\r\033[K%s", line.c_str());
    std::fflush(stderr);
  }

  std::mutex mutex_;
  std::condition_variable tick_;
  std::thread ticker_;
  bool stopping_ = false;
  const std::size_t total_;
  const int jobs_;
  const bool terminal_;
  const std::atomic<bool>* cancel_;
  const std::shared_ptr<spdlog::logger> log_;
  const Clock::time_point start_ = Clock::now();
  std::set<std::string> running_;
  std::size_t done_ = 0;
  int baked_ = 0, failed_ = 0;
  double baked_seconds_ = 0;
};

}  // namespace

PresetOverrides jobOverrides(const LibraryJob& job, const LibraryBakeOptions& options) {
  PresetOverrides out;
  for (const auto& set : options.sets) {
    out.sets.push_back(set);
    out.set_origins.push_back("--set " + set);
  }
  if (job.wedge) {
    out.sets.insert(out.sets.end(), job.wedge->sets.begin(), job.wedge->sets.end());
    out.set_origins.insert(out.set_origins.end(), job.wedge->set_origins.begin(), job.wedge->set_origins.end());
  }
  out.seed = job.seed;
  out.resolution = options.resolution;
  return out;
}

LibraryBakeResult bakeLibrary(const Library& library, const std::vector<LibraryJob>& jobs,
                              const LibraryBakeOptions& options) {
  const auto run_start = Clock::now();
  const fs::path base_dir = fs::absolute(library.file).parent_path();
  const int jobs_at_once = std::max(1, options.jobs);
  const int cores = options.threads > 0 ? options.threads : int(std::max(1u, std::thread::hardware_concurrency()));
  const int render_threads = std::max(1, cores / jobs_at_once);
  const auto cancelled = [&] { return options.cancel && options.cancel->load(); };
  fs::create_directories(options.out_dir);

  Progress progress(jobs.size(), jobs_at_once, options.terminal, options.cancel);
  std::vector<JobOutcome> outcomes(jobs.size());
  for (std::size_t i = 0; i < jobs.size(); ++i) outcomes[i].index = i;

  const auto run_job = [&](std::size_t i) {
    const LibraryJob& job = jobs[i];
    const LibraryEntry& entry = library.entries[job.entry];
    const fs::path asset_dir = options.out_dir / job.name;
    JobOutcome outcome;
    outcome.index = i;
    const auto start = Clock::now();
    const auto seconds = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };

    const PresetOverrides overrides = jobOverrides(job, options);
    ManifestInputs inputs;
    inputs.base_dir = base_dir;
    inputs.preset_file = entry.preset;
    inputs.overrides = overrides;
    if (job.wedge) inputs.wedge = job.wedge->name, inputs.wedge_sets = job.wedge->sets;
    inputs.library_file = library.file.filename().string();
    inputs.library_sha256 = library.sha256;

    progress.started(job.name);
    std::string out_of_memory = "out of memory while reading the job's inputs";
    try {
      Preset preset = loadPreset(entry.preset_file, overrides);
      out_of_memory =
          fmt::format("out of memory: lower grid.resolution ({} needs about {} MiB for the simulation alone)",
                      preset.grid.resolution, estimateSimulationBytes(computeGridLayout(preset)) >> 20);
      preset.name = job.name;  // the asset is the job: OUT/<job>/, and the name in its headers
      const double load_seconds = seconds();
      if (isCompleteAsset(asset_dir, bakeInputHash(preset, options.mesh, options.render, base_dir))) {
        outcome.status = Status::Skipped;
      } else {
        BakeOptions bake;
        bake.out_dir = options.out_dir;
        bake.mesh = options.mesh;
        bake.render = options.render;
        bake.render_threads = render_threads;
        bake.load_seconds = load_seconds;
        bake.manifest = inputs;
        bake.cancel = options.cancel;
        // Isolated, so that a thread waiting inside this job's parallel loops does not pick up
        // another whole job and hold this one up until that one ends.
        tbb::this_task_arena::isolate([&] { bakeAsset(preset, bake); });
        outcome.status = Status::Baked;
      }
    } catch (const BakeCancelled&) {
      outcome.status = Status::NotRun;
    } catch (const std::exception& e) {
      if (cancelled()) {
        outcome.status = Status::NotRun;  // e.g. POV-Ray stopped by the same Ctrl-C
      } else {
        outcome.status = Status::Failed;
        const bool no_memory = dynamic_cast<const std::bad_alloc*>(&e) || dynamic_cast<const std::length_error*>(&e);
        outcome.message = no_memory ? out_of_memory : escapeControlBytes(e.what());
        try {
          beginAssetFolder(asset_dir);  // drop an earlier bake's manifest: this job's inputs no longer match it
          writeFailureRecord(asset_dir, job.name, inputs, outcome.message, seconds());
        } catch (const std::exception& write_error) {
          outcome.message += fmt::format(" (and its failure record could not be written: {})", write_error.what());
        }
      }
    }
    outcome.seconds = seconds();
    progress.finished(job.name, outcome);
    return outcome;
  };

  std::size_t next = 0;
  tbb::parallel_pipeline(
      std::size_t(jobs_at_once),
      tbb::make_filter<void, std::size_t>(tbb::filter_mode::serial_in_order,
                                          [&](tbb::flow_control& control) -> std::size_t {
                                            if (next == jobs.size() || cancelled()) {
                                              control.stop();
                                              return 0;
                                            }
                                            return next++;
                                          }) &
          tbb::make_filter<std::size_t, JobOutcome>(tbb::filter_mode::parallel, run_job) &
          tbb::make_filter<JobOutcome, void>(tbb::filter_mode::serial_out_of_order,
                                             [&](JobOutcome outcome) { outcomes[outcome.index] = outcome; }));
  progress.finish();

  LibraryBakeResult result;
  result.cancelled = cancelled();
  std::map<std::string, std::string> run_status;
  nlohmann::ordered_json statuses = nlohmann::ordered_json::object();
  for (const auto& outcome : outcomes) {
    const std::string& name = jobs[outcome.index].name;
    switch (outcome.status) {
      case Status::Baked:
        ++result.baked;
        statuses[name] = "baked";
        break;
      case Status::Skipped:
        ++result.skipped;
        statuses[name] = "skipped-resumed";
        run_status[name] = "skipped-resumed";
        break;
      case Status::Failed:
        ++result.failed;
        statuses[name] = "failed";
        break;
      case Status::NotRun:
        ++result.not_run;
        statuses[name] = "not-run";
        break;
    }
  }
  nlohmann::ordered_json timings;
  timings["seconds"] = std::chrono::duration<double>(Clock::now() - run_start).count();
  timings["jobs"] = jobs_at_once;
  timings["threads"] = cores;
  timings["cancelled"] = result.cancelled;
  timings["this_run"] = statuses;
  writeLibraryIndex(options.out_dir, run_status, timings);
  return result;
}

}  // namespace rockbake
