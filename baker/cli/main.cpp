// rockbake's command line (docs/command-line.md). Exit status: 0 success, 2 bad preset or
// arguments, 1 any other failure; every failure prints what to fix.
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>
#include <tbb/global_control.h>
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "cli/library_progress.h"
#include "core/error.h"
#include "delivery/blender_library.h"
#include "pipeline/asset_folder.h"
#include "pipeline/bake_asset.h"
#include "pipeline/checkpoint.h"
#include "pipeline/individual_json.h"
#include "pipeline/library_bake.h"
#include "pipeline/library_index.h"
#include "pipeline/manifest.h"
#include "pipeline/read_inputs.h"
#include "pipeline/rerender_asset.h"
#include "pipeline/resume_plan.h"
#include "platform/abnormal_exit.h"
#include "platform/data_dir.h"
#include "platform/memory.h"
#include "preset/library.h"
#include "preset/load_preset.h"
#include "preset/preset_json.h"
#include "preset/preset_pack.h"
#include "preset/render_templates.h"
#include "render/render_asset.h"
#include "review/review_server.h"
#include "studio/studio_server.h"

namespace {

constexpr int kExitOk = 0;
constexpr int kExitFailure = 1;
constexpr int kExitBadInput = 2;
constexpr int kExitInterrupted = 130;  // 128 + SIGINT, as shells report Ctrl-C

// What to say when memory runs out while `preset` is being baked (nullptr: while reading inputs).
std::string outOfMemoryMessage(const rockbake::Preset* preset) {
  return preset ? rockbake::outOfMemoryMessage(*preset) : "out of memory while reading the inputs";
}

// --seed: a whole number from 0 to 2^64 - 1, written as digits (CLI11 would wrap "-1" to 2^64 - 1).
const CLI::Validator kSeedValidator(
    [](std::string& text) -> std::string {
      const bool digits = !text.empty() && text.size() <= 20 &&
                          std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
      if (!digits || (text.size() == 20 && text > "18446744073709551615"))
        return "must be a whole number from 0 to 18446744073709551615, found '" + text + "'";
      return {};
    },
    "UINT64");

// --threads N: at most N TBB workers while the returned object lives; 0 leaves all cores.
std::unique_ptr<tbb::global_control> limitThreads(int threads) {
  if (threads <= 0) return nullptr;
  return std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
}

// ---- options more than one subcommand takes, declared once ----

// --resolution takes what grid.resolution takes.
const CLI::Range kResolutionRange(rockbake::GridParams::kMinResolution, rockbake::GridParams::kMaxResolution);

void addThreads(CLI::App* command, int& threads, const std::string& help = "Worker threads (default: all cores)") {
  command->add_option("--threads", threads, help)->check(CLI::Range(1, 1024));
}

void addOut(CLI::App* command, std::string& out_dir, const std::string& help = "Output folder (default: out)") {
  command->add_option("-o,--out", out_dir, help);
}

void addSets(CLI::App* command, std::vector<std::string>& sets,
             const std::string& help = "Override a preset key: key.path=YAML value (repeatable)") {
  command->add_option("--set", sets, help);
}

void addSeed(CLI::App* command, std::optional<std::uint64_t>& seed, const std::string& help) {
  command->add_option("--seed", seed, help)->check(kSeedValidator);
}

void addResolution(CLI::App* command, std::optional<int>& resolution, const std::string& help) {
  command->add_option("--resolution", resolution, help)->check(kResolutionRange);
}

// What a bake writes: --no-mesh, --no-render, --no-textures.
struct StageSwitches {
  bool no_mesh = false;
  bool no_render = false;
  bool no_textures = false;

  rockbake::BakeStages stages() const { return {!no_mesh, !no_textures, !no_render}; }
};

void addStageSwitches(CLI::App* command, StageSwitches& switches) {
  command->add_flag("--no-mesh", switches.no_mesh, "Skip meshing (and so rendering)");
  command->add_flag("--no-render", switches.no_render, "Skip rendering");
  command->add_flag("--no-textures", switches.no_textures, "Skip the texture set (meshes with vertex colours only)");
}

void addCheckpointEvery(CLI::App* command, double& every, const std::string& help) {
  command->add_option("--checkpoint-every", every, help)->check(CLI::PositiveNumber);
}

// ---- bake ----

struct BakeArgs {
  std::vector<std::string> presets;
  std::string out_dir = "out";
  int threads = 0;
  std::optional<std::uint64_t> seed;
  std::vector<std::string> sets;
  std::optional<int> resolution;
  StageSwitches switches;
  double checkpoint_every = 0.0;
};

CLI::App* declareBake(CLI::App& app, BakeArgs& args) {
  CLI::App* command = app.add_subcommand("bake", "Weather and bake one asset per preset into OUT/<name>/");
  command->add_option("presets", args.presets, "Preset YAML files")->required()->check(CLI::ExistingFile);
  addOut(command, args.out_dir);
  addThreads(command, args.threads);
  addSeed(command, args.seed, "Override the presets' seed");
  addSets(command, args.sets);
  addResolution(command, args.resolution, "Override grid.resolution (voxels along the longest side)");
  addStageSwitches(command, args.switches);
  addCheckpointEvery(command, args.checkpoint_every,
                     "Save the simulation state every T units of time to OUT/<name>/checkpoints/<time>.rbk");
  return command;
}

// Every preset, its files, its render template and the folder it will replace are checked before anything
// is baked, so a problem with the last one does not leave the first ones done.
struct LoadedPresets {
  std::vector<rockbake::Preset> presets;
  std::vector<rockbake::ResolvedShape> shapes;
  std::vector<double> load_seconds;
};

LoadedPresets loadPresetsToBake(const BakeArgs& args, const rockbake::PresetOverrides& overrides) {
  LoadedPresets loaded;
  for (const auto& file : args.presets) {
    const auto start = std::chrono::steady_clock::now();
    loaded.presets.push_back(rockbake::loadPreset(file, overrides));
    loaded.shapes.push_back(rockbake::readInputs(loaded.presets.back()));
    loaded.load_seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  const auto& presets = loaded.presets;
  for (std::size_t i = 0; i < presets.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (presets[i].name == presets[j].name)
        throw rockbake::InputError(presets[i].locate("name"), "name",
                                   "'" + presets[i].name + "' is also the name of " + args.presets[j],
                                   "assets are written to OUT/<name>; give each preset its own name");
  // The render template of every preset exists (the default one too).
  if (args.switches.stages().applied().render)
    for (const auto& preset : presets)
      if (const auto problem =
              rockbake::renderTemplateProblem(preset.render.template_name, rockbake::renderTemplatesDir()))
        throw rockbake::InputError(preset.locate("render.template"), "render.template", *problem);
  for (const auto& preset : presets) rockbake::checkAssetWritable(std::filesystem::path(args.out_dir) / preset.name);
  return loaded;
}

int runBake(const BakeArgs& args) {
  const auto thread_limit = limitThreads(args.threads);
  const rockbake::PresetOverrides overrides{args.sets, args.seed, args.resolution};
  const LoadedPresets loaded = loadPresetsToBake(args, overrides);
  for (std::size_t i = 0; i < loaded.presets.size(); ++i) {
    const rockbake::Preset& preset = loaded.presets[i];
    rockbake::BakeOptions options;
    options.out_dir = args.out_dir;
    options.stages = args.switches.stages();
    options.load_seconds = loaded.load_seconds[i];
    options.render_threads = args.threads;
    options.manifest.overrides = overrides;
    options.checkpoint_every = args.checkpoint_every;
    rockbake::BakeSummary summary;
    try {
      summary = rockbake::bakeAsset(preset, loaded.shapes[i], options);
    } catch (const std::bad_alloc&) {
      throw std::runtime_error(outOfMemoryMessage(&preset));
    } catch (const std::length_error&) {
      throw std::runtime_error(outOfMemoryMessage(&preset));
    }
    spdlog::info("{}: {} cycles, rock {} → {} voxels in {:.2f} s → {}", preset.name, summary.cycles,
                 summary.initial_rock, summary.final_rock, summary.seconds, summary.asset_dir.string());
  }
  return kExitOk;
}

// ---- resume ----

struct ResumeArgs {
  std::string checkpoint;
  std::vector<std::string> sets;
  std::string out_dir = "out";
  int threads = 0;
  StageSwitches switches;
  double checkpoint_every = 0.0;
};

CLI::App* declareResume(CLI::App& app, ResumeArgs& args) {
  CLI::App* command = app.add_subcommand("resume", "Continue a checkpoint, with edits, into OUT/<name>/");
  command->add_option("checkpoint", args.checkpoint, "A .rbk file written by bake --checkpoint-every")
      ->required()
      ->check(CLI::ExistingFile);
  addSets(command, args.sets,
          "Edit: durability.points/noise, bubbles, response (keyframes at the checkpoint's time), colluvium, "
          "rockfall, time (repeatable)");
  addOut(command, args.out_dir);
  addThreads(command, args.threads);
  addStageSwitches(command, args.switches);
  addCheckpointEvery(command, args.checkpoint_every, "Save checkpoints as bake does");
  return command;
}

// Continues a checkpoint (with edits) into OUT/<name>/, as the bake it came from would have gone on.
int runResume(const ResumeArgs& args) {
  const auto thread_limit = limitThreads(args.threads);
  const rockbake::Checkpoint checkpoint = rockbake::readCheckpoint(args.checkpoint);
  rockbake::ResumePlan plan = rockbake::planResume(checkpoint, args.sets);
  rockbake::BakeOptions options;
  options.out_dir = args.out_dir;
  options.stages = args.switches.stages();
  options.render_threads = args.threads;
  options.manifest.overrides = plan.overrides;
  options.checkpoint_every = args.checkpoint_every;
  options.resume = &checkpoint;
  const auto summary = rockbake::bakeAsset(plan.preset, rockbake::readInputs(plan.preset), options);
  spdlog::info("{}: resumed at time {:.4g}, {} cycles in all, rock {} → {} voxels in {:.2f} s → {}", plan.preset.name,
               checkpoint.snapshot.cycle * checkpoint.snapshot.rock.layout.h, summary.cycles, summary.initial_rock,
               summary.final_rock, summary.seconds, summary.asset_dir.string());
  return kExitOk;
}

// ---- render ----

struct RenderArgs {
  std::string asset_dir;
  std::string template_name;
  std::string output;
  int threads = 0;
};

CLI::App* declareRender(CLI::App& app, RenderArgs& args) {
  CLI::App* command = app.add_subcommand("render", "Render a baked asset again, without re-simulating");
  command->add_option("asset_dir", args.asset_dir, "An asset folder written by `rockbake bake` (OUT/<name>)")
      ->required()
      ->check(CLI::ExistingDirectory);
  command->add_option("--template", args.template_name, "A template in render_templates/ (default: the preset's)");
  command->add_option("--output", args.output,
                      "The still's file name, NAME.exr and NAME.png (default: render with the preset's template, "
                      "render_<template> with another)");
  addThreads(command, args.threads, "POV-Ray threads (default: all cores)");
  return command;
}

int runRender(const RenderArgs& args) {
  if (!args.template_name.empty())
    if (const auto problem = rockbake::renderTemplateProblem(args.template_name, rockbake::renderTemplatesDir()))
      throw rockbake::InputError({"--template"}, "", *problem, "give the name of a template, never a path");
  const auto out = rockbake::rerenderAssetFolder({args.asset_dir, args.template_name, args.output, args.threads});
  spdlog::info("rendered {} in {:.1f} s", out.render_png.string(), out.seconds_total);
  return kExitOk;
}

// ---- lint ----

struct LintArgs {
  std::vector<std::string> presets;
  std::vector<std::string> sets;
};

CLI::App* declareLint(CLI::App& app, LintArgs& args) {
  CLI::App* command = app.add_subcommand(
      "lint", "Check presets, the bases they extend and library files; list every problem (file:line:col: key.path)");
  command->add_option("presets", args.presets, "Preset, base or library YAML files, or pack folders")->required();
  addSets(command, args.sets, "Override a key of every preset before checking it (repeatable)");
  return command;
}

// A preset's problems, with the files it names and its grid against this machine's memory, as a bake checks them.
std::vector<rockbake::InputError> lintOnePreset(const std::filesystem::path& file,
                                                const rockbake::PresetOverrides& overrides) {
  std::vector<rockbake::InputError> found = rockbake::lintPreset(file, overrides);
  if (found.empty()) try {
      rockbake::readInputs(rockbake::loadPreset(file, overrides));
    } catch (const rockbake::InputError& e) {
      found.push_back(e);
    }
  return found;
}

// A library's problems: the file's own, then every job's preset with the job's wedge (each preset and
// wedge once).
std::vector<rockbake::InputError> lintLibrary(const std::filesystem::path& file, const std::vector<std::string>& sets,
                                              std::size_t& jobs) {
  std::vector<rockbake::InputError> found;
  try {
    const rockbake::Library library = rockbake::loadLibrary(file);
    jobs = rockbake::expandLibrary(library).size();
    for (const auto& entry : library.entries) {
      std::vector<std::optional<rockbake::LibraryWedge>> wedges(entry.wedges.begin(), entry.wedges.end());
      if (wedges.empty()) wedges.push_back(std::nullopt);
      for (const auto& wedge : wedges) {
        rockbake::PresetOverrides overrides{sets, std::nullopt, std::nullopt};
        if (wedge) {
          overrides.set_origins.assign(sets.size(), "");
          overrides.sets.insert(overrides.sets.end(), wedge->sets.begin(), wedge->sets.end());
          overrides.set_origins.insert(overrides.set_origins.end(), wedge->set_origins.begin(),
                                       wedge->set_origins.end());
        }
        for (auto& problem : lintOnePreset(entry.preset_file, overrides)) found.push_back(std::move(problem));
      }
    }
  } catch (const rockbake::InputError& e) {
    found.push_back(e);
  }
  return found;
}

// A pack (a folder holding pack.json, preset/preset_pack.h): pack.json against the folder, then every
// preset it lists as lintOnePreset checks it.
std::vector<rockbake::InputError> lintPack(const std::filesystem::path& dir,
                                           const rockbake::PresetOverrides& overrides, std::string& what) {
  rockbake::PackCheck check = rockbake::checkPack(dir);
  for (const auto& preset : check.presets)
    for (auto& problem : lintOnePreset(dir / preset, overrides)) check.problems.push_back(std::move(problem));
  what = fmt::format(" (a pack of {} preset{} and {} file{}, every file's SHA-256 checked)", check.presets.size(),
                     check.presets.size() == 1 ? "" : "s", check.files, check.files == 1 ? "" : "s");
  return check.problems;
}

// A preset, base or library file's problems; `what` says what it is when it is a base or a library.
std::vector<rockbake::InputError> lintFile(const std::string& file, const LintArgs& args,
                                           const rockbake::PresetOverrides& overrides, std::string& what) {
  switch (rockbake::presetFileKind(file)) {
    case rockbake::PresetFileKind::Preset:
      return lintOnePreset(file, overrides);
    case rockbake::PresetFileKind::Base:
      what = " (a base: no name, shape or time of its own; presets extend it)";
      return rockbake::lintBase(file, overrides);
    case rockbake::PresetFileKind::Library: {
      std::size_t jobs = 0;
      auto found = lintLibrary(file, args.sets, jobs);
      what = fmt::format(" (a library of {} job{}, every preset checked)", jobs, jobs == 1 ? "" : "s");
      return found;
    }
  }
  return {};
}

// Lists every problem of every file, one per line ("file:line:col: key.path: problem (hint)"), and
// "FILE: ok" for each clean one (saying what it is when it is a base, a library or a pack). A file in a
// pack's folder is checked with its pack.
int runLint(const LintArgs& args) {
  std::size_t problems = 0, failed = 0;
  const rockbake::PresetOverrides overrides{args.sets, std::nullopt, std::nullopt};
  for (const auto& file : args.presets) {
    std::vector<rockbake::InputError> found;
    std::string what;
    const std::filesystem::path folder =
        std::filesystem::path(file).has_parent_path() ? std::filesystem::path(file).parent_path() : ".";
    if (std::filesystem::is_directory(file)) {
      found = lintPack(file, overrides, what);
    } else if (rockbake::isPackFolder(folder)) {
      found = rockbake::checkPack(folder).problems;
      for (auto& problem : lintFile(file, args, overrides, what)) found.push_back(std::move(problem));
      what += " (in a pack: its pack.json checked too)";
    } else {
      found = lintFile(file, args, overrides, what);
    }
    for (const auto& problem : found) std::cout << problem.what() << '\n';
    if (found.empty()) std::cout << file << ": ok" << what << "\n";
    problems += found.size();
    failed += found.empty() ? 0 : 1;
  }
  std::cout.flush();
  if (failed == 0) return kExitOk;
  spdlog::error("{} problem{} in {} of {} file{}", problems, problems == 1 ? "" : "s", failed, args.presets.size(),
                args.presets.size() == 1 ? "" : "s");
  return kExitBadInput;
}

// ---- preset show ----

struct PresetShowArgs {
  std::string preset;
  std::vector<std::string> sets;
  std::optional<std::uint64_t> seed;
  std::optional<int> resolution;
  bool individual = false;
};

CLI::App* declarePresetShow(CLI::App& app, PresetShowArgs& args) {
  CLI::App* preset = app.add_subcommand("preset", "Inspect and share presets");
  preset->require_subcommand(1);
  CLI::App* command = preset->add_subcommand(
      "show", "Print the resolved preset as JSON: extends merged, overrides applied, every default filled in");
  command->add_option("preset", args.preset, "A preset YAML file")->required();
  addSets(command, args.sets);
  addSeed(command, args.seed, "Override the preset's seed");
  addResolution(command, args.resolution, "Override grid.resolution");
  command->add_flag("--individual", args.individual,
                    "Print what the seed draws from the preset's family (docs/model.md §12) instead");
  return command;
}

// Prints the preset as a bake would run it: extends merged, overrides applied, every default filled in
// (the JSON stats.json embeds).
int runPresetShow(const PresetShowArgs& args) {
  const rockbake::Preset preset = rockbake::loadPreset(args.preset, {args.sets, args.seed, args.resolution});
  if (args.individual && !preset.family)
    throw rockbake::InputError(preset.locate(""), "family",
                               "the preset has no family: every seed weathers its "
                               "blockout as given",
                               "add a family: block (docs/preset-reference.md)");
  std::cout << (args.individual ? rockbake::individualJson(preset).dump(2) : rockbake::presetToJson(preset).dump(2))
            << std::endl;
  return kExitOk;
}

// ---- preset pack ----

struct PresetPackArgs {
  std::vector<std::string> presets;
  std::string out_dir;
};

// A subcommand of `preset` (declarePresetShow made it).
CLI::App* declarePresetPack(CLI::App& app, PresetPackArgs& args) {
  CLI::App* command = app.get_subcommand("preset")->add_subcommand(
      "pack", "Bundle presets with every file they reach (bases, images, blockouts) into a folder to share");
  command->add_option("presets", args.presets, "Preset YAML files, all in one folder")->required();
  command->add_option("-o,--out", args.out_dir, "The pack folder: new, empty, or a pack to replace")->required();
  return command;
}

int runPresetPack(const PresetPackArgs& args) {
  const std::vector<std::filesystem::path> presets(args.presets.begin(), args.presets.end());
  const rockbake::PackSummary pack = rockbake::packPresets(presets, args.out_dir);
  spdlog::info("{} {}: {} preset{}, {} file{} ({} bytes){}; bake it with `rockbake bake {}`",
               pack.replaced ? "replaced" : "wrote", pack.dir.string(), pack.presets.size(),
               pack.presets.size() == 1 ? "" : "s", pack.files, pack.files == 1 ? "" : "s", pack.bytes,
               pack.rewritten ? fmt::format(", {} path{} rewritten to the pack's copies", pack.rewritten,
                                            pack.rewritten == 1 ? "" : "s")
                              : "",
               (pack.dir / pack.presets.front()).string());
  return kExitOk;
}

// ---- studio ----

struct StudioArgs {
  std::string preset;
  std::string out_dir = "out";
  rockbake::StudioOptions options;
};

CLI::App* declareStudio(CLI::App& app, StudioArgs& args) {
  CLI::App* command = app.add_subcommand(
      "studio", "Edit the durability graph while the rock weathers, in a local web page (docs/studio.md)");
  command->add_option("preset", args.preset, "A preset YAML file")->required()->check(CLI::ExistingFile);
  command->add_option("--port", args.options.port, "TCP port (default: 8631; 0: any free port)")
      ->check(CLI::Range(0, 65535));
  command->add_option("--host", args.options.host, "Address to listen on (default: 127.0.0.1, this machine only)");
  command->add_option("--resolution", args.options.resolution, "Preview resolution (default: 64)")
      ->check(CLI::Range(8, 2048));
  addOut(command, args.out_dir, "Where bake final writes OUT/<name>/ (default: out)");
  return command;
}

int runStudio(StudioArgs args) {
  args.options.preset = args.preset;
  args.options.out_dir = args.out_dir;
  args.options.web_root = rockbake::requireDataPath("studio");
  return rockbake::runStudio(args.options);
}

// ---- review ----

struct ReviewArgs {
  std::string library_dir;
  rockbake::ReviewOptions options;
};

CLI::App* declareReview(CLI::App& app, ReviewArgs& args) {
  CLI::App* command = app.add_subcommand(
      "review", "Review a baked library in a local web page: turntables, 3-D views, verdicts (docs/review.md)");
  command->add_option("out", args.library_dir, "The library folder (holding index.json)")
      ->required()
      ->check(CLI::ExistingDirectory);
  command->add_option("--port", args.options.port, "TCP port (default: 8632; 0: any free port)")
      ->check(CLI::Range(0, 65535));
  command->add_option("--host", args.options.host, "Address to listen on (default: 127.0.0.1, this machine only)");
  return command;
}

// A folder of plain bakes (`rockbake bake -o OUT`) has asset folders but no index: it is indexed
// first, as `rockbake library --index-only OUT` does, so that review serves it.
void indexPlainBakes(const std::filesystem::path& out) {
  namespace fs = std::filesystem;
  if (!fs::is_directory(out) || fs::exists(out / rockbake::kIndexFile)) return;
  std::error_code ec;
  bool any = false;
  for (const auto& entry : fs::directory_iterator(out, ec))
    any = any || (entry.is_directory() && fs::is_regular_file(entry.path() / rockbake::kManifestFile));
  if (!any) return;
  const auto counts = rockbake::writeLibraryIndex(out, {}, {{"index_only", true}});
  spdlog::info("review: indexed {} ({} assets ok, {} failed, {} damaged), as `rockbake library --index-only` does",
               out.string(), counts.ok + counts.skipped_resumed, counts.failed, counts.damaged);
}

int runReview(ReviewArgs args) {
  indexPlainBakes(args.library_dir);
  args.options.library_dir = args.library_dir;
  args.options.web_root = rockbake::requireDataPath("review");
  args.options.three_root = rockbake::requireDataPath("studio") / "node_modules" / "three";
  return rockbake::runReview(args.options);
}

// ---- library ----

struct LibraryArgs {
  std::string library;
  std::string out_dir = "out";
  std::string index_only;
  std::string shard;
  int jobs = 1;
  int threads = 0;
  std::vector<std::string> sets;
  std::optional<int> resolution;
  StageSwitches switches;
};

CLI::App* declareLibrary(CLI::App& app, LibraryArgs& args) {
  CLI::App* command = app.add_subcommand(
      "library", "Bake every job of a library file (presets × seeds × wedges) into OUT/<job>/, with an index");
  command->add_option("library", args.library, "Library YAML file")->check(CLI::ExistingFile);
  addOut(command, args.out_dir);
  command->add_option("--jobs", args.jobs, "Jobs baked at once (default: 1)")->check(CLI::Range(1, 256));
  command->add_option("--shard", args.shard, "Bake only shard I of N (I/N, from 0): every N-th job")->type_name("I/N");
  command
      ->add_option("--index-only", args.index_only,
                   "Only rebuild OUT/index.json and contact_sheet.png from the asset folders in OUT")
      ->type_name("OUT")
      ->excludes("library")
      ->excludes("--out")
      ->excludes("--shard");
  addThreads(command, args.threads);
  addSets(command, args.sets, "Override a key of every job's preset, before its wedge (repeatable)");
  addResolution(command, args.resolution, "Override grid.resolution of every job");
  addStageSwitches(command, args.switches);
  return command;
}

std::atomic<bool> library_interrupted{false};

extern "C" void onLibraryInterrupt(int) {
  library_interrupted.store(true);
}

// SIGINT / SIGTERM: finish cleanly (no new jobs; running ones stop at the next stage boundary). The
// handler is one-shot, so a second Ctrl-C ends the process at once.
void installLibraryInterruptHandlers() {
  struct sigaction action {};
  action.sa_handler = onLibraryInterrupt;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESETHAND;
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

// `rockbake library --index-only OUT`: exit 1 when a folder is damaged.
int runLibraryIndexOnly(const std::string& out_dir) {
  namespace fs = std::filesystem;
  if (!fs::is_directory(out_dir))
    throw rockbake::InputError({out_dir}, "", "not a folder", "give the OUT folder the shards baked into");
  const auto counts = rockbake::writeLibraryIndex(out_dir, {}, {{"index_only", true}});
  spdlog::info("{}: {} assets ok, {} failed, {} damaged", (fs::path(out_dir) / rockbake::kIndexFile).string(),
               counts.ok + counts.skipped_resumed, counts.failed, counts.damaged);
  return counts.damaged > 0 ? kExitFailure : kExitOk;
}

// The run's end in one line, and its exit status: 130 interrupted, 1 when a job failed, else 0.
int reportLibraryRun(const rockbake::LibraryBakeResult& result, const std::string& out_dir) {
  const std::string summary =
      fmt::format("{} baked, {} already complete, {} failed{} → {}", result.baked, result.skipped, result.failed,
                  result.not_run ? fmt::format(", {} not run", result.not_run) : "",
                  (std::filesystem::path(out_dir) / rockbake::kIndexFile).string());
  if (result.cancelled) {
    spdlog::warn("interrupted: {}; run the same command again to finish", summary);
    return kExitInterrupted;
  }
  if (result.failed > 0) {
    spdlog::error("{}; see the messages above or index.json", summary);
    return kExitFailure;
  }
  spdlog::info("{}", summary);
  return kExitOk;
}

// `rockbake library`: every job of a library file (or of one shard of it), then the index. Exit status 0 when
// every job baked or was already complete, 1 when any failed, 130 when interrupted, 2 for a bad library file,
// bad arguments or job folders it may not write (nothing is written then).
int runLibrary(const LibraryArgs& args, bool verbose) {
  if (!args.index_only.empty()) return runLibraryIndexOnly(args.index_only);
  if (args.library.empty())
    throw rockbake::InputError({"<command line>"}, "", "a library file is needed (or --index-only OUT)",
                               "rockbake library LIBRARY.yaml -o OUT");
  // Everything the command line and the library file say is checked before anything is written.
  const rockbake::Shard shard = args.shard.empty() ? rockbake::Shard{} : rockbake::parseShard(args.shard);
  const rockbake::Library library = rockbake::loadLibrary(args.library);
  const auto all_jobs = rockbake::expandLibrary(library);
  const auto jobs = rockbake::selectShard(all_jobs, shard);

  const auto thread_limit = limitThreads(args.threads);
  rockbake::LibraryBakeOptions options;
  options.out_dir = args.out_dir;
  options.jobs = args.jobs;
  options.threads = args.threads;
  options.sets = args.sets;
  options.resolution = args.resolution;
  options.stages = args.switches.stages();
  options.cancel = &library_interrupted;
  rockbake::LibraryProgress progress(jobs.size(), std::max(1, args.jobs), ::isatty(STDERR_FILENO) == 1,
                                     &library_interrupted);
  options.observer = progress.observer();
  spdlog::info("{}: {} jobs{}, {} at once → {}", args.library, jobs.size(),
               shard.count > 1 ? fmt::format(" (shard {}/{} of {})", shard.index, shard.count, all_jobs.size()) : "",
               options.jobs, args.out_dir);
  // The jobs' own per-cycle logs would bury the progress lines; --verbose brings them back.
  if (!verbose) spdlog::set_level(spdlog::level::warn);
  installLibraryInterruptHandlers();
  const auto result = rockbake::bakeLibrary(library, jobs, options);
  progress.finish();
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
  if (!verbose) spdlog::set_level(spdlog::level::info);
  return reportLibraryRun(result, args.out_dir);
}

// ---- blender-library ----

struct BlenderLibraryArgs {
  std::vector<std::string> sources;
  std::string out_dir;
  std::string blender;
  int jobs = 1;
  int threads = 0;
};

CLI::App* declareBlenderLibrary(CLI::App& app, BlenderLibraryArgs& args) {
  CLI::App* command = app.add_subcommand(
      "blender-library",
      "Make a Blender asset library (one .blend per asset, with catalogues) from baked assets (docs/libraries.md)");
  command->add_option("sources", args.sources, "Baked library folders (OUT of rockbake library) or asset folders")
      ->required();
  command->add_option("-o,--out", args.out_dir, "The Blender asset library folder to write")->required();
  command->add_option("--blender", args.blender,
                      "The Blender executable (default: $ROCKBAKE_BLENDER, else blender on PATH)");
  command->add_option("--jobs", args.jobs, "Blender processes at once (default: 1)")->check(CLI::Range(1, 64));
  addThreads(command, args.threads, "Cores shared among the Blender processes (default: all)");
  return command;
}

// `rockbake blender-library SOURCE... -o OUT`: exit status 0 when every asset was written, 1 when Blender
// failed on any (the others are written), 2 for bad sources, a missing Blender or an OUT it may not write
// (nothing is written then).
int runBlenderLibrary(const BlenderLibraryArgs& args) {
  rockbake::BlenderLibraryOptions options;
  options.sources.assign(args.sources.begin(), args.sources.end());
  options.out_dir = args.out_dir;
  options.blender = args.blender;
  options.jobs = args.jobs;
  options.threads = args.threads;
  const auto result = rockbake::writeBlenderLibrary(options);
  const std::string summary =
      fmt::format("{} written, {} failed{}{} → {}", result.written, result.failed,
                  result.skipped ? fmt::format(", {} asset folders skipped", result.skipped) : "",
                  result.removed ? fmt::format(", {} earlier .blend files removed", result.removed) : "", args.out_dir);
  if (result.failed > 0) {
    spdlog::error("{}; see the messages above", summary);
    return kExitFailure;
  }
  spdlog::info("{}", summary);
  return kExitOk;
}

// ---- the command line ----

// `what` run, its failures turned into exit statuses: 2 for what the user gave (InputError), 1 otherwise,
// with a sentence for running out of memory.
int exitStatusOf(const std::function<int()>& what) {
  try {
    return what();
  } catch (const rockbake::InputError& e) {
    spdlog::error("{}", e.what());
    return kExitBadInput;
  } catch (const std::bad_alloc&) {
    spdlog::error("{}", outOfMemoryMessage(nullptr));
    return kExitFailure;
  } catch (const std::length_error&) {  // a container asked for more than it can ever hold
    spdlog::error("{}", outOfMemoryMessage(nullptr));
    return kExitFailure;
  } catch (const std::exception& e) {
    // Helper programs' messages (POV-Ray's parse error, FFmpeg's) come as lines: kept as lines.
    spdlog::error("{}", rockbake::escapeControlBytesKeepingLines(e.what()));
    return kExitFailure;
  }
}

}  // namespace

int main(int argc, char** argv) {
  rockbake::installAbnormalExitHandler();
  rockbake::returnLargeBlocksToTheSystem();
  auto logger = spdlog::stderr_color_mt("rockbake");
  logger->set_pattern("%^%l%$: %v");
  spdlog::set_default_logger(logger);

  CLI::App app{"rockbake: bakes weathered rock assets from YAML presets"};
  app.set_version_flag("--version", std::string("rockbake ") + ROCKBAKE_VERSION);
  app.require_subcommand(1);
  bool verbose = false;
  app.add_flag("-v,--verbose", verbose, "Log every stage in detail");
  app.fallthrough();  // the subcommands hand -v on: `rockbake bake P -v` as well as `rockbake -v bake P`

  BakeArgs bake;
  ResumeArgs resume;
  RenderArgs render;
  LintArgs lint;
  PresetShowArgs preset_show;
  PresetPackArgs preset_pack;
  StudioArgs studio;
  ReviewArgs review;
  LibraryArgs library;
  BlenderLibraryArgs blender_library;
  // Each subcommand, declared, and what runs when it is the one given.
  const std::vector<std::pair<CLI::App*, std::function<int()>>> subcommands = {
      {declareBake(app, bake), [&] { return runBake(bake); }},
      {declareResume(app, resume), [&] { return runResume(resume); }},
      {declareRender(app, render), [&] { return runRender(render); }},
      {declareLint(app, lint), [&] { return runLint(lint); }},
      {declarePresetShow(app, preset_show), [&] { return runPresetShow(preset_show); }},
      {declarePresetPack(app, preset_pack), [&] { return runPresetPack(preset_pack); }},
      {declareStudio(app, studio), [&] { return runStudio(studio); }},
      {declareReview(app, review), [&] { return runReview(review); }},
      {declareLibrary(app, library), [&] { return runLibrary(library, verbose); }},
      {declareBlenderLibrary(app, blender_library), [&] { return runBlenderLibrary(blender_library); }},
  };

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return kExitBadInput;
  }
  if (verbose) spdlog::set_level(spdlog::level::debug);
  for (const auto& [command, run] : subcommands)
    if (*command) return exitStatusOf(run);
  return kExitFailure;
}
