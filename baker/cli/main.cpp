// rockbake's command line (SPEC §6). Exit status: 0 success, 2 bad preset or
// arguments, 1 any other failure; every failure prints what to fix.
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
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
#include "pipeline/bake_asset.h"
#include "pipeline/library_bake.h"
#include "pipeline/library_index.h"
#include "pipeline/manifest.h"
#include "pipeline/read_inputs.h"
#include "pipeline/rerender_asset.h"
#include "preset/library.h"
#include "preset/load_preset.h"
#include "preset/preset_json.h"
#include "render/render_asset.h"

namespace {

constexpr int kExitOk = 0;
constexpr int kExitFailure = 1;
constexpr int kExitBadInput = 2;
constexpr int kExitInterrupted = 130;  // 128 + SIGINT, as shells report Ctrl-C

// --threads N: at most N TBB workers while the returned object lives; 0 leaves all cores.
std::unique_ptr<tbb::global_control> limitThreads(int threads) {
  if (threads <= 0) return nullptr;
  return std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
}

struct BakeArgs {
  std::vector<std::string> presets;
  std::string out_dir = "out";
  int threads = 0;
  std::optional<std::uint64_t> seed;
  std::vector<std::string> sets;
  std::optional<int> resolution;
  bool no_mesh = false;
  bool no_render = false;
};

// --resolution takes what grid.resolution takes.
const CLI::Range kResolutionRange(rockbake::GridParams::kMinResolution, rockbake::GridParams::kMaxResolution);

int runBake(const BakeArgs& args) {
  const auto thread_limit = limitThreads(args.threads);
  rockbake::PresetOverrides overrides{args.sets, args.seed, args.resolution};

  // Every preset is validated before anything is baked, so a typo in the
  // last one does not leave the first ones half done.
  std::vector<rockbake::Preset> presets;
  std::vector<rockbake::ResolvedShape> shapes;
  std::vector<double> load_seconds;
  for (const auto& file : args.presets) {
    const auto start = std::chrono::steady_clock::now();
    presets.push_back(rockbake::loadPreset(file, overrides));
    shapes.push_back(rockbake::readInputs(presets.back()));
    load_seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  for (std::size_t i = 0; i < presets.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (presets[i].name == presets[j].name)
        throw rockbake::InputError({args.presets[i]}, "name",
                                   "'" + presets[i].name + "' is also the name of " + args.presets[j],
                                   "assets are written to OUT/<name>; give each preset its own name");

  for (std::size_t i = 0; i < presets.size(); ++i) {
    rockbake::BakeOptions options;
    options.out_dir = args.out_dir;
    options.mesh = !args.no_mesh;
    options.render = !args.no_render;
    options.load_seconds = load_seconds[i];
    options.render_threads = args.threads;
    options.manifest.overrides = overrides;
    const auto summary = rockbake::bakeAsset(presets[i], shapes[i], options);
    spdlog::info("{}: {} cycles, rock {} → {} voxels in {:.2f} s → {}", presets[i].name, summary.cycles,
                 summary.initial_rock, summary.final_rock, summary.seconds, summary.asset_dir.string());
  }
  return kExitOk;
}

struct RenderArgs {
  std::string asset_dir;
  std::string template_name;
  int threads = 0;
};

int runRender(const RenderArgs& args) {
  const auto out = rockbake::rerenderAssetFolder({args.asset_dir, args.template_name, args.threads});
  spdlog::info("rendered {} in {:.1f} s", out.render_png.string(), out.seconds_total);
  return kExitOk;
}

struct LintArgs {
  std::vector<std::string> presets;
};

// Lists every problem of every preset, one per line ("file:line:col: key.path: problem (hint)"), and
// "FILE: ok" for each clean one.
int runLint(const LintArgs& args) {
  std::size_t problems = 0, failed = 0;
  for (const auto& file : args.presets) {
    std::vector<rockbake::InputError> found = rockbake::lintPreset(file);
    // The files the preset names, and the grid against this machine's memory, as a bake checks them.
    if (found.empty()) try {
        rockbake::readInputs(rockbake::loadPreset(file));
      } catch (const rockbake::InputError& e) {
        found.push_back(e);
      }
    for (const auto& problem : found) std::cout << problem.what() << '\n';
    if (found.empty()) std::cout << file << ": ok\n";
    problems += found.size();
    failed += found.empty() ? 0 : 1;
  }
  std::cout.flush();
  if (failed == 0) return kExitOk;
  spdlog::error("{} problem{} in {} of {} preset{}", problems, problems == 1 ? "" : "s", failed, args.presets.size(),
                args.presets.size() == 1 ? "" : "s");
  return kExitBadInput;
}

struct PresetShowArgs {
  std::string preset;
  std::vector<std::string> sets;
  std::optional<std::uint64_t> seed;
  std::optional<int> resolution;
};

// Prints the preset as a bake would run it: extends merged, overrides applied, every default filled in
// (the JSON stats.json embeds).
int runPresetShow(const PresetShowArgs& args) {
  const rockbake::Preset preset = rockbake::loadPreset(args.preset, {args.sets, args.seed, args.resolution});
  std::cout << rockbake::presetToJson(preset).dump(2) << std::endl;
  return kExitOk;
}

struct LibraryArgs {
  std::string library;
  std::string out_dir = "out";
  std::string index_only;
  std::string shard;
  int jobs = 1;
  int threads = 0;
  std::vector<std::string> sets;
  std::optional<int> resolution;
  bool no_mesh = false;
  bool no_render = false;
};

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

// `rockbake library`: every job of a library file (or of one shard of it), then the index. Exit status 0 when
// every job baked or was already complete, 1 when any failed, 130 when interrupted, 2 for a bad library file
// or bad arguments (nothing is written then).
int runLibrary(const LibraryArgs& args, bool verbose) {
  namespace fs = std::filesystem;
  if (!args.index_only.empty()) {
    if (!fs::is_directory(args.index_only))
      throw rockbake::InputError({args.index_only}, "", "not a folder", "give the OUT folder the shards baked into");
    const auto counts = rockbake::writeLibraryIndex(args.index_only, {}, {{"index_only", true}});
    spdlog::info("{}: {} assets ok, {} failed", (fs::path(args.index_only) / rockbake::kIndexFile).string(),
                 counts.ok + counts.skipped_resumed, counts.failed);
    return kExitOk;
  }
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
  options.mesh = !args.no_mesh;
  options.render = !args.no_render && !args.no_mesh;
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

  const std::string summary =
      fmt::format("{} baked, {} already complete, {} failed{} → {}", result.baked, result.skipped, result.failed,
                  result.not_run ? fmt::format(", {} not run", result.not_run) : "",
                  (fs::path(args.out_dir) / rockbake::kIndexFile).string());
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

}  // namespace

int main(int argc, char** argv) {
  auto logger = spdlog::stderr_color_mt("rockbake");
  logger->set_pattern("%^%l%$: %v");
  spdlog::set_default_logger(logger);

  CLI::App app{"rockbake: bakes weathered rock assets from YAML presets"};
  app.set_version_flag("--version", std::string("rockbake ") + ROCKBAKE_VERSION);
  app.require_subcommand(1);
  bool verbose = false;
  app.add_flag("-v,--verbose", verbose, "Log every stage in detail");

  BakeArgs bake;
  CLI::App* bake_cmd = app.add_subcommand("bake", "Weather and bake one asset per preset into OUT/<name>/");
  bake_cmd->add_option("presets", bake.presets, "Preset YAML files")->required()->check(CLI::ExistingFile);
  bake_cmd->add_option("-o,--out", bake.out_dir, "Output folder (default: out)");
  bake_cmd->add_option("--threads", bake.threads, "Worker threads (default: all cores)")->check(CLI::Range(1, 1024));
  bake_cmd->add_option("--seed", bake.seed, "Override the presets' seed");
  bake_cmd->add_option("--set", bake.sets, "Override a preset key: key.path=YAML value (repeatable)");
  bake_cmd->add_option("--resolution", bake.resolution, "Override grid.resolution (voxels along the longest side)")
      ->check(kResolutionRange);
  bake_cmd->add_flag("--no-mesh", bake.no_mesh, "Skip meshing (and so rendering)");
  bake_cmd->add_flag("--no-render", bake.no_render, "Skip rendering");

  RenderArgs render;
  CLI::App* render_cmd = app.add_subcommand("render", "Render a baked asset again, without re-simulating");
  render_cmd->add_option("asset_dir", render.asset_dir, "An asset folder written by `rockbake bake` (OUT/<name>)")
      ->required()
      ->check(CLI::ExistingDirectory);
  render_cmd->add_option("--template", render.template_name, "A template in render_templates/ (default: the preset's)");
  render_cmd->add_option("--threads", render.threads, "POV-Ray threads (default: all cores)")
      ->check(CLI::Range(1, 1024));

  LintArgs lint;
  CLI::App* lint_cmd =
      app.add_subcommand("lint", "Check presets and list every problem (file:line:col: key.path: problem)");
  lint_cmd->add_option("presets", lint.presets, "Preset YAML files")->required();

  PresetShowArgs preset_show;
  CLI::App* preset_cmd = app.add_subcommand("preset", "Inspect presets");
  preset_cmd->require_subcommand(1);
  CLI::App* preset_show_cmd = preset_cmd->add_subcommand(
      "show", "Print the resolved preset as JSON: extends merged, overrides applied, every default filled in");
  preset_show_cmd->add_option("preset", preset_show.preset, "A preset YAML file")->required();
  preset_show_cmd->add_option("--set", preset_show.sets, "Override a preset key: key.path=YAML value (repeatable)");
  preset_show_cmd->add_option("--seed", preset_show.seed, "Override the preset's seed");
  preset_show_cmd->add_option("--resolution", preset_show.resolution, "Override grid.resolution")
      ->check(kResolutionRange);

  LibraryArgs library;
  CLI::App* library_cmd = app.add_subcommand(
      "library", "Bake every job of a library file (presets × seeds × wedges) into OUT/<job>/, with an index");
  library_cmd->add_option("library", library.library, "Library YAML file")->check(CLI::ExistingFile);
  library_cmd->add_option("-o,--out", library.out_dir, "Output folder (default: out)");
  library_cmd->add_option("--jobs", library.jobs, "Jobs baked at once (default: 1)")->check(CLI::Range(1, 256));
  library_cmd->add_option("--shard", library.shard, "Bake only shard I of N (I/N, from 0): every N-th job")
      ->type_name("I/N");
  library_cmd
      ->add_option("--index-only", library.index_only,
                   "Only rebuild OUT/index.json and contact_sheet.png from the asset folders in OUT")
      ->type_name("OUT")
      ->excludes("library")
      ->excludes("--out")
      ->excludes("--shard");
  library_cmd->add_option("--threads", library.threads, "Worker threads (default: all cores)")
      ->check(CLI::Range(1, 1024));
  library_cmd->add_option("--set", library.sets, "Override a key of every job's preset, before its wedge (repeatable)");
  library_cmd->add_option("--resolution", library.resolution, "Override grid.resolution of every job")
      ->check(kResolutionRange);
  library_cmd->add_flag("--no-mesh", library.no_mesh, "Skip meshing (and so rendering)");
  library_cmd->add_flag("--no-render", library.no_render, "Skip rendering");

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

  try {
    if (*bake_cmd) return runBake(bake);
    if (*render_cmd) return runRender(render);
    if (*lint_cmd) return runLint(lint);
    if (*preset_show_cmd) return runPresetShow(preset_show);
    if (*library_cmd) return runLibrary(library, verbose);
  } catch (const rockbake::InputError& e) {
    spdlog::error("{}", e.what());
    return kExitBadInput;
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return kExitFailure;
  }
  return kExitFailure;
}
