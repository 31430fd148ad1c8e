#include "pipeline/bake_asset.h"

#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>

#include <chrono>
#include <cmath>
#include <fstream>
#include <memory>
#include <sstream>
#include <system_error>

#include <fmt/format.h>
#include <spdlog/spdlog.h>
#include <nlohmann/json.hpp>

#include "core/abnormal_exit.h"
#include "core/atomic_file.h"
#include "core/error.h"
#include "core/stopwatch.h"
#include "export/vdb_file.h"
#include "pipeline/asset_json.h"
#include "pipeline/bake_meshes.h"
#include "pipeline/manifest.h"
#include "pipeline/read_inputs.h"
#include "preset/preset_json.h"
#include "render/render_asset.h"
#include "sim/grid_layout.h"
#include "sim/shapes.h"
#include "sim/weathering.h"

namespace rockbake {
namespace {

// A bake writes into a hidden folder beside its asset folder, OUT/.<name>.baking-<pid>, and renames it into
// place only when everything, manifest.json last, is written: a bake that fails or is interrupted leaves
// the previous complete asset, or nothing (not even OUT, when the bake created it).
class StagingFolder {
 public:
  // `out_of_memory`: what to say should the process end without unwinding (core/abnormal_exit.h), which
  // removes the folder then too.
  StagingFolder(const std::filesystem::path& asset_dir, const std::string& out_of_memory)
      : final_(asset_dir),
        staging_(hidden(asset_dir, "baking")),
        created_out_(!std::filesystem::exists(asset_dir.parent_path().empty() ? "." : asset_dir.parent_path())),
        on_abnormal_exit_(staging_, out_of_memory, created_out_) {
    removeStale(asset_dir);
    std::filesystem::remove_all(staging_);
    std::filesystem::create_directories(staging_);
  }
  StagingFolder(const StagingFolder&) = delete;
  StagingFolder& operator=(const StagingFolder&) = delete;
  ~StagingFolder() {
    if (committed_) return;
    std::error_code ignored;
    std::filesystem::remove_all(staging_, ignored);
    if (created_out_) std::filesystem::remove(final_.parent_path(), ignored);  // only if still empty
  }

  const std::filesystem::path& path() const { return staging_; }

  // The previous asset (if any) is moved aside, the new one renamed into place, then the old one removed.
  void commit() {
    const std::filesystem::path old = hidden(final_, "replaced");
    std::error_code ignored;
    std::filesystem::remove_all(old, ignored);
    if (std::filesystem::exists(std::filesystem::symlink_status(final_))) std::filesystem::rename(final_, old);
    std::filesystem::rename(staging_, final_);
    committed_ = true;
    std::filesystem::remove_all(old, ignored);
  }

 private:
  // What a killed bake of this asset left (.<name>.baking-<pid>, .<name>.replaced-<pid> of a process that is
  // gone) is removed; a bake of it still running elsewhere is left alone.
  static void removeStale(const std::filesystem::path& asset_dir) {
    std::error_code ec;
    const std::filesystem::path parent = asset_dir.parent_path().empty() ? "." : asset_dir.parent_path();
    const std::string prefix = "." + asset_dir.filename().string() + ".";
    for (const auto& entry : std::filesystem::directory_iterator(parent, ec)) {
      const std::string name = entry.path().filename().string();
      if (name.rfind(prefix, 0) != 0) continue;
      const std::size_t dash = name.rfind('-');
      const std::string kind = name.substr(prefix.size(), dash == std::string::npos ? 0 : dash - prefix.size());
      if (dash == std::string::npos || (kind != "baking" && kind != "replaced")) continue;
      const long pid = std::strtol(name.c_str() + dash + 1, nullptr, 10);
      if (pid > 0 && ::kill(pid_t(pid), 0) != 0 && errno == ESRCH) std::filesystem::remove_all(entry.path(), ec);
    }
  }

  static std::filesystem::path hidden(const std::filesystem::path& dir, const char* what) {
    // Appended piece by piece: GCC 12 warns (-Wrestrict, a false positive) about "." + std::string.
    std::string name = ".";
    name += dir.filename().string();
    name += '.';
    name += what;
    name += '-';
    name += std::to_string(::getpid());
    return dir.parent_path() / name;
  }

  std::filesystem::path final_, staging_;
  bool created_out_ = false;
  bool committed_ = false;
  OnAbnormalExit on_abnormal_exit_;
};

std::string readTextFile(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + file.string() + " for its checkpoints");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

nlohmann::ordered_json cyclesToJson(const std::vector<CycleStats>& cycles) {
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (const auto& c : cycles)
    list.push_back({{"cycle", c.cycle},
                    {"time", c.time},
                    {"rock", c.rock},
                    {"exposed", c.exposed},
                    {"decimated", c.decimated},
                    {"colluvium", c.colluvium},
                    {"fallen", c.fallen},
                    {"removed", c.removed},
                    {"deposited", c.deposited},
                    {"crumbled", c.crumbled}});
  return list;
}

}  // namespace

BakeSummary bakeAsset(const Preset& preset, const BakeOptions& options) {
  return bakeAsset(preset, readInputs(preset), options);
}

BakeSummary bakeAsset(const Preset& preset, const ResolvedShape& shape, const BakeOptions& options) {
  BakeSummary summary;
  summary.asset_dir = options.out_dir / preset.name;
  nlohmann::ordered_json stages;
  stages["load"] = options.load_seconds;
  Stopwatch clock;
  StagingFolder staging(summary.asset_dir, outOfMemoryMessage(preset));
  const std::filesystem::path& dir = staging.path();
  const AssetFolderSnapshot before = beginAssetFolder(dir);
  const auto progress = [&](double fraction, const char* stage) {
    if (options.progress) options.progress(fraction, stage);
  };
  const auto check_cancel = [&] {
    if (options.cancel && options.cancel->load()) throw BakeCancelled();
  };

  // The simulation runs cycle by cycle so that its state can be checkpointed,
  // or started from a checkpoint (docs/libraries.md).
  std::unique_ptr<WeatheringSimulation> simulation;
  nlohmann::ordered_json cycles_before =
      nlohmann::ordered_json::array();  // a resumed bake's cycles up to its checkpoint
  if (options.resume) {
    const GridLayout& was = options.resume->snapshot.rock.layout;
    const GridLayout now = computeGridLayout(preset);
    if (was.nx != now.nx || was.ny != now.ny || was.nz != now.nz || was.margin != now.margin || was.h != now.h)
      throw InputError(preset.locate("grid"), "grid",
                       fmt::format("the checkpoint's grid is {}×{}×{} voxels of {:.4g} and this preset's {}×{}×{} of "
                                   "{:.4g}",
                                   was.nx, was.ny, was.nz, was.h, now.nx, now.ny, now.nz, now.h),
                       "grid, shape, resolution and bubbles larger than the checkpoint's margin cannot change on "
                       "resume; bake from the start instead");
    simulation = std::make_unique<WeatheringSimulation>(options.resume->snapshot, preset);
    summary.initial_rock = options.resume->snapshot.initial_rock;
    cycles_before = options.resume->cycles;
  } else {
    VoxelRock initial = buildInitialRock(shape, preset);
    if (initial.count(Material::Rock) == 0)
      throw InputError(preset.locate("shape"), "shape", "the shape covers no voxel of the grid",
                       "check its size and center against grid.size, or raise grid.resolution");
    summary.initial_rock = initial.count(Material::Rock);
    simulation = std::make_unique<WeatheringSimulation>(std::move(initial), preset);
  }
  const GridLayout g = simulation->rock().layout;
  stages["shape"] = clock.lap();
  const int planned = plannedCycles(preset, g.h);
  spdlog::info("{}: {}×{}×{} voxels of {:.4g} units, {} rock voxels, {} cycles{}", preset.name, g.nx, g.ny, g.nz, g.h,
               summary.initial_rock, planned,
               options.resume ? fmt::format(" (resumed at cycle {})", simulation->cycle()) : "");

  // Checkpoints: the text and overrides that give this preset, so resume can
  // read it again and tell whether it changed.
  Checkpoint checkpoint;
  const double every = options.checkpoint_every;
  double next_checkpoint = 0.0;
  if (every > 0.0) {
    checkpoint.preset_file = std::filesystem::absolute(preset.file);
    checkpoint.preset_text = options.resume ? options.resume->preset_text : readTextFile(preset.file);
    checkpoint.overrides = options.manifest.overrides;
    checkpoint.preset = presetToJson(preset);
    checkpoint.preset_hash = presetFingerprint(preset, {});
    next_checkpoint = every * (std::floor(simulation->cycle() * g.h / every + 1e-9) + 1.0);
  }

  int last_percent = -1;
  WeatheringResult weathered;
  while (!simulation->finished()) {
    const CycleStats& c = weathered.cycles.emplace_back(simulation->step());
    check_cancel();
    progress(0.7 * c.cycle / planned, "simulate");
    const int percent = 100 * c.cycle / planned;
    if (percent / 10 != last_percent / 10) {
      spdlog::info("{}: cycle {}/{} ({}%), {} rock, {} exposed, {} decimated", preset.name, c.cycle, planned, percent,
                   c.rock, c.exposed, c.decimated);
      last_percent = percent;
    }
    if (every > 0.0 && c.time >= next_checkpoint - 1e-9 * g.h && !simulation->finished()) {
      checkpoint.snapshot = simulation->snapshot();
      checkpoint.cycles = cycles_before;
      for (const auto& entry : cyclesToJson(weathered.cycles)) checkpoint.cycles.push_back(entry);
      const auto file = dir / "checkpoints" / checkpointFileName(c.time);
      writeCheckpoint(file, checkpoint);
      spdlog::info("{}: checkpoint {}", preset.name, file.string());
      while (next_checkpoint <= c.time + 1e-9 * g.h) next_checkpoint += every;
    }
  }
  // The curvature attribute is the exposure under the bubble graph in effect
  // at the end: the latest keyframe's, when one carried bubbles.
  Preset meshing = preset;
  meshing.bubbles = simulation->activeParams().bubbles;
  weathered.rock = simulation->release();
  // Its working state (air field, bit planes, work lists) is not needed past here.
  simulation.reset();
  stages["simulate"] = clock.lap();
  double curvature = 0, colluvium = 0, rockfall = 0;
  for (const auto& c : weathered.cycles)
    curvature += c.curvature_seconds, colluvium += c.colluvium_seconds, rockfall += c.rockfall_seconds;
  stages["simulate_curvature"] = curvature;
  stages["simulate_colluvium"] = colluvium;
  stages["simulate_rockfall"] = rockfall;
  summary.cycles = int(cycles_before.size() + weathered.cycles.size());
  summary.final_rock = weathered.rock.count(Material::Rock);
  // No later stage reads integrity: its memory goes before the VDB and meshes.
  weathered.rock.integrity = RowSpans();

  check_cancel();
  if (!options.mesh) {
    writeRockVdb(weathered.rock, dir / "rock.vdb");
    stages["write_vdb"] = clock.lap();
  } else {
    progress(0.7, "mesh");
    const MeshStageResult meshes = bakeMeshes(weathered.rock, meshing, dir);
    stages["mesh_extract"] = meshes.extract_seconds;
    stages["mesh_subdivide"] = meshes.subdivide_seconds;
    stages["mesh_attributes"] = meshes.attributes_seconds;
    stages["mesh_simplify"] = meshes.simplify_seconds;
    stages["export"] = meshes.export_seconds;
    clock.lap();
    // rock_sdf in the VDB is the field the meshes were made from.
    if (exportsFormat(preset, "vdb")) {
      writeRockVdb(weathered.rock, dir / "rock.vdb", meshes.rock_sdf.get());
      stages["write_vdb"] = clock.lap();
    }

    if (options.render) {
      check_cancel();
      progress(0.85, "render");
      RenderRequest request;
      request.asset_dir = dir;
      request.params = preset.render;
      request.preset_name = preset.name;
      request.seed = preset.seed;
      request.preset_hash = presetFingerprint(preset, options.manifest);
      request.threads = options.render_threads;
      request.cancel = options.cancel;
      const RenderOutputs rendered = renderAsset(meshes.meshes, request);
      stages["render"] = rendered.seconds_total;
      spdlog::info("{}: rendered {} in {:.1f} s", preset.name,
                   (summary.asset_dir / rendered.render_png.filename()).string(), rendered.seconds_total);
      clock.lap();
    }

    AssetDescription asset;
    asset.name = preset.name;
    asset.tags = preset.tags;
    asset.units_per_meter = preset.units_per_meter;
    asset.lods.push_back({meshes.lod_files.at(0), &meshes.meshes});
    for (std::size_t i = 0; i < meshes.lods.size(); ++i)
      asset.lods.push_back({meshes.lod_files.at(i + 1), &meshes.lods[i]});
    asset.preview = options.render ? "render.png" : "";
    const std::filesystem::path base =
        options.manifest.base_dir.empty() ? preset.file.parent_path() : options.manifest.base_dir;
    asset.input_hash = bakeInputHash(preset, options.mesh, options.render, base);
    writeAssetJson(asset, dir);
  }

  summary.seconds = clock.elapsed();
  stages["total"] = summary.seconds + options.load_seconds;
  nlohmann::ordered_json stats;
  nlohmann::ordered_json all_cycles = cycles_before;
  for (const auto& entry : cyclesToJson(weathered.cycles)) all_cycles.push_back(entry);
  stats["cycles"] = all_cycles;
  stats["stages"] = stages;
  stats["preset"] = presetToJson(preset);
  check_cancel();
  writeFileAtomically(dir / "stats.json", stats.dump(2) + "\n");
  const ManifestStats manifest_stats{summary.cycles, summary.initial_rock, summary.final_rock,
                                     weathered.rock.count(Material::Colluvium)};
  writeManifest(before, preset, options.manifest, options.mesh, options.render, manifest_stats, {{"stages", stages}});
  staging.commit();
  progress(1.0, "done");
  return summary;
}

}  // namespace rockbake
