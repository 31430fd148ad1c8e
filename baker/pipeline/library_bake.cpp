#include "pipeline/library_bake.h"

#include <algorithm>
#include <chrono>
#include <memory>
#include <optional>
#include <thread>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>
#include <tbb/parallel_pipeline.h>
#include <tbb/task_arena.h>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "pipeline/asset_folder.h"
#include "pipeline/bake_asset.h"
#include "pipeline/library_index.h"
#include "pipeline/manifest.h"
#include "pipeline/read_inputs.h"

namespace rockbake {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

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

namespace {

// What every job of one run shares.
struct LibraryRun {
  const Library& library;
  const std::vector<LibraryJob>& jobs;
  const LibraryBakeOptions& options;
  fs::path base_dir;  // the library file's folder: inputs are recorded relative to it
  int render_threads = 1;
  bool cancelled() const { return options.cancel && options.cancel->load(); }
};

// Before anything is written: OUT is a folder, and no job's folder is foreign or being written by another
// live process (pipeline/asset_folder.h). Every refused folder is named, the first as the InputError.
void checkJobFolders(const std::vector<LibraryJob>& jobs, const fs::path& out_dir) {
  checkOutFolder(out_dir);
  std::vector<std::string> refused;
  std::optional<InputError> first;
  for (const auto& job : jobs) {
    try {
      checkAssetWritable(out_dir / job.name);
    } catch (const InputError& e) {
      if (!first) first = e;
      refused.push_back(job.name);
    }
  }
  if (refused.size() > 1)
    spdlog::error("{} job folders cannot be written: {}{}", refused.size(),
                  fmt::join(refused.begin(), refused.begin() + std::min<std::ptrdiff_t>(refused.size(), 20), ", "),
                  refused.size() > 20 ? ", …" : "");
  if (first) throw *first;
}

ManifestInputs jobInputs(const LibraryRun& run, const LibraryJob& job) {
  ManifestInputs inputs;
  inputs.base_dir = run.base_dir;
  inputs.preset_file = run.library.entries[job.entry].preset;
  inputs.overrides = jobOverrides(job, run.options);
  if (job.wedge) inputs.wedge = job.wedge->name, inputs.wedge_sets = job.wedge->sets;
  inputs.library_file = run.library.file.filename().string();
  inputs.library_sha256 = run.library.sha256;
  return inputs;
}

// failure.json in the job's folder, under its lock, written before the earlier bake's manifest goes
// (this job's inputs no longer match it), so the folder always reads as one of ours. A folder that is not
// rockbake's gets nothing.
void recordFailure(const fs::path& asset_dir, const std::string& job, const ManifestInputs& inputs,
                   std::string& message, double seconds) {
  try {
    if (const auto problem = foreignAssetProblem(asset_dir)) {
      message += " (no failure record: " + asset_dir.string() + " " + *problem + ")";
      return;
    }
    writeFailureRecord(asset_dir, job, inputs, message, seconds);
    fs::remove(asset_dir / kManifestFile);
  } catch (const std::exception& write_error) {
    message += fmt::format(" (and its failure record could not be written: {})", write_error.what());
  }
}

// One job, under its asset's lock: skipped when its folder already holds it, else baked; a failure is
// recorded in failure.json.
JobOutcome bakeJob(const LibraryRun& run, std::size_t i) {
  const LibraryJob& job = run.jobs[i];
  const fs::path asset_dir = run.options.out_dir / job.name;
  JobOutcome outcome;
  outcome.index = i;
  const auto start = Clock::now();
  const auto seconds = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };
  const ManifestInputs inputs = jobInputs(run, job);
  if (run.options.observer.started) run.options.observer.started(job.name);
  std::string out_of_memory = "out of memory while reading the job's inputs";
  std::unique_ptr<AssetLock> lock;
  try {
    lock = std::make_unique<AssetLock>(asset_dir);
    tidyAssetFolder(*lock);
    Preset preset = loadPreset(run.library.entries[job.entry].preset_file, inputs.overrides);
    out_of_memory = outOfMemoryMessage(preset);
    preset.name = job.name;  // the asset is the job: OUT/<job>/, and the name in its headers
    const double load_seconds = seconds();
    BakeOptions bake;
    bake.out_dir = run.options.out_dir;
    bake.stages = run.options.stages;
    if (isCompleteAsset(asset_dir, bakeInputHash(presetAsBaked(preset, bake), bake.stages, run.base_dir))) {
      outcome.status = JobStatus::Skipped;
    } else {
      bake.render_threads = run.render_threads;
      bake.load_seconds = load_seconds;
      bake.manifest = inputs;
      bake.cancel = run.options.cancel;
      bake.lock = lock.get();
      // Isolated, so that a thread waiting inside this job's parallel loops does not pick up
      // another whole job and hold this one up until that one ends.
      tbb::this_task_arena::isolate([&] { bakeAsset(preset, bake); });
      outcome.status = JobStatus::Baked;
    }
  } catch (const BakeCancelled&) {
    outcome.status = JobStatus::NotRun;
  } catch (const std::exception& e) {
    if (run.cancelled()) {
      outcome.status = JobStatus::NotRun;  // e.g. POV-Ray stopped by the same Ctrl-C
    } else {
      outcome.status = JobStatus::Failed;
      const bool no_memory = dynamic_cast<const std::bad_alloc*>(&e) || dynamic_cast<const std::length_error*>(&e);
      outcome.message = no_memory ? out_of_memory : escapeControlBytes(e.what());
      // Without the lock the folder is another process's: nothing is written to it.
      if (lock) recordFailure(asset_dir, job.name, inputs, outcome.message, seconds());
    }
  }
  lock.reset();
  outcome.seconds = seconds();
  if (run.options.observer.finished) run.options.observer.finished(job.name, outcome);
  return outcome;
}

// The outcomes counted, and the index written with this run's timings.
LibraryBakeResult finishRun(const LibraryRun& run, const std::vector<JobOutcome>& outcomes, double seconds,
                            int jobs_at_once, int cores) {
  static const std::map<JobStatus, const char*> kStatusName = {{JobStatus::Baked, "baked"},
                                                               {JobStatus::Skipped, "skipped-resumed"},
                                                               {JobStatus::Failed, "failed"},
                                                               {JobStatus::NotRun, "not-run"}};
  LibraryBakeResult result;
  result.cancelled = run.cancelled();
  std::map<std::string, std::string> run_status;
  nlohmann::ordered_json statuses = nlohmann::ordered_json::object();
  for (const auto& outcome : outcomes) {
    const std::string& name = run.jobs[outcome.index].name;
    statuses[name] = kStatusName.at(outcome.status);
    if (outcome.status == JobStatus::Skipped) run_status[name] = "skipped-resumed";
    switch (outcome.status) {
      case JobStatus::Baked:
        ++result.baked;
        break;
      case JobStatus::Skipped:
        ++result.skipped;
        break;
      case JobStatus::Failed:
        ++result.failed;
        break;
      case JobStatus::NotRun:
        ++result.not_run;
        break;
    }
  }
  nlohmann::ordered_json timings;
  timings["seconds"] = seconds;
  timings["jobs"] = jobs_at_once;
  timings["threads"] = cores;
  timings["cancelled"] = result.cancelled;
  timings["this_run"] = statuses;
  writeLibraryIndex(run.options.out_dir, run_status, timings);
  return result;
}

}  // namespace

LibraryBakeResult bakeLibrary(const Library& library, const std::vector<LibraryJob>& jobs,
                              const LibraryBakeOptions& options) {
  const auto run_start = Clock::now();
  checkJobFolders(jobs, options.out_dir);
  const int jobs_at_once = std::max(1, options.jobs);
  const int cores = options.threads > 0 ? options.threads : int(std::max(1u, std::thread::hardware_concurrency()));
  const LibraryRun run{library, jobs, options, fs::absolute(library.file).parent_path(),
                       std::max(1, cores / jobs_at_once)};
  fs::create_directories(options.out_dir);

  std::vector<JobOutcome> outcomes(jobs.size());
  for (std::size_t i = 0; i < jobs.size(); ++i) outcomes[i].index = i;
  std::size_t next = 0;
  tbb::parallel_pipeline(
      std::size_t(jobs_at_once),
      tbb::make_filter<void, std::size_t>(tbb::filter_mode::serial_in_order,
                                          [&](tbb::flow_control& control) -> std::size_t {
                                            if (next == jobs.size() || run.cancelled()) {
                                              control.stop();
                                              return 0;
                                            }
                                            return next++;
                                          }) &
          tbb::make_filter<std::size_t, JobOutcome>(tbb::filter_mode::parallel,
                                                    [&](std::size_t i) { return bakeJob(run, i); }) &
          tbb::make_filter<JobOutcome, void>(tbb::filter_mode::serial_out_of_order,
                                             [&](JobOutcome outcome) { outcomes[outcome.index] = outcome; }));
  return finishRun(run, outcomes, std::chrono::duration<double>(Clock::now() - run_start).count(), jobs_at_once, cores);
}

}  // namespace rockbake
