// BakeLibrary: every job of a library (or of one shard of it) as a TBB
// pipeline, one asset folder per job, then the index (docs/libraries.md).
//
//   jobs ─▶ [serial: next job] ─▶ [parallel: load preset, resume check, bakeAsset]
//        ─▶ [serial: record, progress] ─▶ index.json + contact_sheet.png
//
// At most `jobs` jobs run at once (the pipeline's tokens), so at most `jobs`
// POV-Ray processes; each gets cores / jobs threads. Simulation and meshing
// are parallel inside each job. Outputs do not depend on `jobs` or `threads`.
//
// Before anything is written, every job's folder is checked as a bake checks
// its own (pipeline/asset_folder.h): OUT must be a folder, and a job folder
// that rockbake did not write, or that another live process is writing,
// refuses the whole run with an InputError naming it (exit 2). Each job holds
// its asset's lock while it runs, so two runs into one OUT (or shards that
// overlap) never write one asset at once: a job whose lock another process
// took meanwhile fails, naming it, and writes nothing.
//
// Resume: a job whose folder holds a complete manifest with the job's input
// hash (pipeline/manifest.h) is skipped. A job that fails (bad preset, POV-Ray
// failure) leaves failure.json with its message; the others go on. When
// `cancel` turns true, no new job starts, running ones stop at their next
// cycle or stage boundary without a manifest, and the index is written for
// what finished.
#pragma once

#include <atomic>
#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "pipeline/bake_stages.h"
#include "preset/library.h"
#include "preset/load_preset.h"

namespace rockbake {

enum class JobStatus { Baked, Skipped, Failed, NotRun };

struct JobOutcome {
  std::size_t index = 0;  // in the job list
  JobStatus status = JobStatus::NotRun;
  std::string message;  // Failed: what went wrong
  double seconds = 0;
};

// Told of each job as it starts and ends (the command line's progress display),
// from the pipeline's threads: calls may come from several threads at once.
struct LibraryObserver {
  std::function<void(const std::string& job)> started;
  std::function<void(const std::string& job, const JobOutcome& outcome)> finished;
};

struct LibraryBakeOptions {
  std::filesystem::path out_dir = "out";
  int jobs = 1;                   // jobs at once, >= 1
  int threads = 0;                // cores to share among the jobs' POV-Ray runs; 0: all
  std::vector<std::string> sets;  // --set, applied to every job before its wedge
  std::optional<int> resolution;  // --resolution
  BakeStages stages;              // every job's (pipeline/bake_stages.h)
  const std::atomic<bool>* cancel = nullptr;
  LibraryObserver observer;
};

struct LibraryBakeResult {
  int baked = 0;
  int skipped = 0;
  int failed = 0;
  int not_run = 0;  // cancelled before they started or while running
  bool cancelled = false;
};

// The overrides one job's preset is loaded with: `sets` (the command line's,
// then the wedge's), the job's seed, --resolution; `set_origins` says where
// each set came from ("--set ..." or "lib.yaml:12:9 (wedge 'tall')"), so an
// error in a wedge points at the library file.
PresetOverrides jobOverrides(const LibraryJob& job, const LibraryBakeOptions& options);

LibraryBakeResult bakeLibrary(const Library& library, const std::vector<LibraryJob>& jobs,
                              const LibraryBakeOptions& options);

}  // namespace rockbake
