#include "pipeline/library_bake.h"

#include <algorithm>
#include <chrono>
#include <thread>

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <tbb/parallel_pipeline.h>
#include <tbb/task_arena.h>
#include <nlohmann/json.hpp>

#include "core/error.h"
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

LibraryBakeResult bakeLibrary(const Library& library, const std::vector<LibraryJob>& jobs,
                              const LibraryBakeOptions& options) {
  const auto run_start = Clock::now();
  const fs::path base_dir = fs::absolute(library.file).parent_path();
  const int jobs_at_once = std::max(1, options.jobs);
  const int cores = options.threads > 0 ? options.threads : int(std::max(1u, std::thread::hardware_concurrency()));
  const int render_threads = std::max(1, cores / jobs_at_once);
  const auto cancelled = [&] { return options.cancel && options.cancel->load(); };
  fs::create_directories(options.out_dir);

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

    if (options.observer.started) options.observer.started(job.name);
    std::string out_of_memory = "out of memory while reading the job's inputs";
    try {
      Preset preset = loadPreset(entry.preset_file, overrides);
      out_of_memory = outOfMemoryMessage(preset);
      preset.name = job.name;  // the asset is the job: OUT/<job>/, and the name in its headers
      const double load_seconds = seconds();
      if (isCompleteAsset(asset_dir, bakeInputHash(preset, options.mesh, options.render, base_dir))) {
        outcome.status = JobStatus::Skipped;
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
        outcome.status = JobStatus::Baked;
      }
    } catch (const BakeCancelled&) {
      outcome.status = JobStatus::NotRun;
    } catch (const std::exception& e) {
      if (cancelled()) {
        outcome.status = JobStatus::NotRun;  // e.g. POV-Ray stopped by the same Ctrl-C
      } else {
        outcome.status = JobStatus::Failed;
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
    if (options.observer.finished) options.observer.finished(job.name, outcome);
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

  LibraryBakeResult result;
  result.cancelled = cancelled();
  std::map<std::string, std::string> run_status;
  nlohmann::ordered_json statuses = nlohmann::ordered_json::object();
  for (const auto& outcome : outcomes) {
    const std::string& name = jobs[outcome.index].name;
    switch (outcome.status) {
      case JobStatus::Baked:
        ++result.baked;
        statuses[name] = "baked";
        break;
      case JobStatus::Skipped:
        ++result.skipped;
        statuses[name] = "skipped-resumed";
        run_status[name] = "skipped-resumed";
        break;
      case JobStatus::Failed:
        ++result.failed;
        statuses[name] = "failed";
        break;
      case JobStatus::NotRun:
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
