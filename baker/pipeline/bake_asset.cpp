#include "pipeline/bake_asset.h"

#include <chrono>

#include <spdlog/spdlog.h>
#include <nlohmann/json.hpp>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/stopwatch.h"
#include "export/vdb_file.h"
#include "pipeline/bake_meshes.h"
#include "pipeline/read_inputs.h"
#include "preset/preset_json.h"
#include "render/render_asset.h"
#include "sim/shapes.h"
#include "sim/weathering.h"

namespace rockbake {
namespace {

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
  const AssetFolderSnapshot before = beginAssetFolder(summary.asset_dir);
  const auto check_cancel = [&] {
    if (options.cancel && options.cancel->load()) throw BakeCancelled();
  };

  VoxelRock initial = buildInitialRock(shape, preset);
  if (initial.count(Material::Rock) == 0)
    throw InputError(preset.locate("shape"), "shape", "the shape covers no voxel of the grid",
                     "check its size and center against grid.size, or raise grid.resolution");
  const GridLayout& g = initial.layout;
  summary.initial_rock = initial.count(Material::Rock);
  stages["shape"] = clock.lap();
  const int planned = plannedCycles(preset, g.h);
  spdlog::info("{}: {}×{}×{} voxels of {:.4g} units, {} rock voxels, {} cycles", preset.name, g.nx, g.ny, g.nz, g.h,
               summary.initial_rock, planned);

  int last_percent = -1;
  WeatheringResult weathered = weatherRock(std::move(initial), preset, [&](const CycleStats& c) {
    check_cancel();
    const int percent = 100 * c.cycle / planned;
    if (percent / 10 != last_percent / 10) {
      spdlog::info("{}: cycle {}/{} ({}%), {} rock, {} exposed, {} decimated", preset.name, c.cycle, planned, percent,
                   c.rock, c.exposed, c.decimated);
      last_percent = percent;
    }
  });
  stages["simulate"] = clock.lap();
  double curvature = 0, colluvium = 0, rockfall = 0;
  for (const auto& c : weathered.cycles)
    curvature += c.curvature_seconds, colluvium += c.colluvium_seconds, rockfall += c.rockfall_seconds;
  stages["simulate_curvature"] = curvature;
  stages["simulate_colluvium"] = colluvium;
  stages["simulate_rockfall"] = rockfall;
  summary.cycles = int(weathered.cycles.size());
  summary.final_rock = weathered.rock.count(Material::Rock);

  check_cancel();
  if (!options.mesh) {
    writeRockVdb(weathered.rock, summary.asset_dir / "rock.vdb");
    stages["write_vdb"] = clock.lap();
  } else {
    const MeshStageResult meshes = bakeMeshes(weathered.rock, preset, summary.asset_dir);
    stages["mesh_extract"] = meshes.extract_seconds;
    stages["mesh_subdivide"] = meshes.subdivide_seconds;
    stages["mesh_attributes"] = meshes.attributes_seconds;
    stages["export"] = meshes.export_seconds;
    clock.lap();
    // rock_sdf in the VDB is the field the meshes were made from.
    if (exportsFormat(preset, "vdb")) {
      writeRockVdb(weathered.rock, summary.asset_dir / "rock.vdb", meshes.rock_sdf.get());
      stages["write_vdb"] = clock.lap();
    }

    if (options.render) {
      check_cancel();
      RenderRequest request;
      request.asset_dir = summary.asset_dir;
      request.params = preset.render;
      request.preset_name = preset.name;
      request.seed = preset.seed;
      request.preset_hash = presetFingerprint(preset, options.manifest);
      request.threads = options.render_threads;
      request.cancel = options.cancel;
      const RenderOutputs rendered = renderAsset(meshes.meshes, request);
      stages["render"] = rendered.seconds_total;
      spdlog::info("{}: rendered {} in {:.1f} s", preset.name, rendered.render_png.string(), rendered.seconds_total);
      clock.lap();
    }
  }

  summary.seconds = clock.elapsed();
  stages["total"] = summary.seconds + options.load_seconds;
  nlohmann::ordered_json stats;
  stats["cycles"] = cyclesToJson(weathered.cycles);
  stats["stages"] = stages;
  stats["preset"] = presetToJson(preset);
  check_cancel();
  writeFileAtomically(summary.asset_dir / "stats.json", stats.dump(2) + "\n");
  const ManifestStats manifest_stats{summary.cycles, summary.initial_rock, summary.final_rock,
                                     weathered.rock.count(Material::Colluvium)};
  writeManifest(before, preset, options.manifest, options.mesh, options.render, manifest_stats, {{"stages", stages}});
  return summary;
}

}  // namespace rockbake
