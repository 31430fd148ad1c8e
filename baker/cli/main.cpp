// rockbake's command line (SPEC §6). Exit status: 0 success, 2 bad preset or
// arguments, 1 any other failure; every failure prints what to fix.
#include <chrono>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>
#include <tbb/global_control.h>
#include <CLI/CLI.hpp>

#include "pipeline/bake_asset.h"
#include "preset/load_preset.h"
#include "util/error.h"

namespace {

constexpr int kExitOk = 0;
constexpr int kExitFailure = 1;
constexpr int kExitBadInput = 2;

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

int runBake(const BakeArgs& args) {
  std::unique_ptr<tbb::global_control> thread_limit;
  if (args.threads > 0)
    thread_limit =
        std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, std::size_t(args.threads));
  rockbake::PresetOverrides overrides{args.sets, args.seed, args.resolution};

  // Every preset is validated before anything is baked, so a typo in the
  // last one does not leave the first ones half done.
  std::vector<rockbake::Preset> presets;
  std::vector<double> load_seconds;
  for (const auto& file : args.presets) {
    const auto start = std::chrono::steady_clock::now();
    presets.push_back(rockbake::loadPreset(file, overrides));
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
    const auto summary = rockbake::bakeAsset(presets[i], options);
    spdlog::info("{}: {} cycles, rock {} → {} voxels in {:.2f} s → {}", presets[i].name, summary.cycles,
                 summary.initial_rock, summary.final_rock, summary.seconds, summary.asset_dir.string());
  }
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
      ->check(CLI::Range(8, 2048));
  bake_cmd->add_flag("--no-mesh", bake.no_mesh, "Skip meshing (and so rendering)");
  bake_cmd->add_flag("--no-render", bake.no_render, "Skip rendering");

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
  } catch (const rockbake::InputError& e) {
    spdlog::error("{}", e.what());
    return kExitBadInput;
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return kExitFailure;
  }
  return kExitFailure;
}
