#include "pipeline/bake_meshes.h"

#include "core/mesh_checks.h"
#include "core/stopwatch.h"

#include <algorithm>
#include <chrono>
#include <limits>
#include <string>

#include <spdlog/spdlog.h>
#include <tbb/task_group.h>

#include "export/glb_file.h"
#include "export/obj_file.h"
#include "export/ply_file.h"
#include "mesh/bake_attributes.h"
#include "mesh/extract_surfaces.h"
#include "mesh/simplify_lods.h"
#include "mesh/subdivide.h"
#include "sim/weathering.h"

namespace rockbake {

bool exportsFormat(const Preset& preset, const std::string& format) {
  return std::find(preset.exports.begin(), preset.exports.end(), format) != preset.exports.end();
}

MeshStageResult buildMeshes(const VoxelRock& rock, const Preset& preset) {
  MeshStageResult r;
  Stopwatch clock;
  AssetMeshes meshes = extractSurfaces(rock, {preset.mesh.smoothing}, &r.rock_sdf);
  r.extract_seconds = clock.lap();

  const std::vector<float> exposure = exposureField(rock, preset);
  meshes = sampleAttributes(std::move(meshes), {&rock, &exposure});
  r.attributes_seconds = clock.lap();

  const SubdivideParams levels{preset.mesh.subdivision};
  meshes.rock = subdivideSurface(meshes.rock, levels);
  meshes.colluvium = subdivideSurface(meshes.colluvium, levels);
  r.subdivide_seconds = clock.lap();
  updateBounds(meshes);

  meshes = applyPalette(std::move(meshes), paletteParams(rock, preset.bake));
  r.attributes_seconds += clock.lap();
  spdlog::debug("{}: rock {} vertices, {} triangles; colluvium {} vertices, {} triangles", preset.name,
                meshes.rock.positions.size(), meshes.rock.triangles.size(), meshes.colluvium.positions.size(),
                meshes.colluvium.triangles.size());

  r.meshes = std::move(meshes);
  return r;
}

MeshStageResult bakeMeshes(const VoxelRock& rock, const Preset& preset, const std::filesystem::path& asset_dir) {
  MeshStageResult r = buildMeshes(rock, preset);
  const AssetMeshes& meshes = r.meshes;
  const Stopwatch export_clock;

  // The files are independent: write them concurrently, so one file's
  // formatting or simplification overlaps another's disk writes and fsync.
  const auto timed = [&](const char* what, auto&& write) {
    return [&, what, write] {
      Stopwatch clock;
      write();
      spdlog::debug("{}: {} in {:.3f} s", preset.name, what, clock.lap());
    };
  };
  tbb::task_group exports;
  if (exportsFormat(preset, "ply")) {
    exports.run(timed("rock.ply", [&] { writePly(meshes.rock, asset_dir / "rock.ply"); }));
    if (!meshes.colluvium.positions.empty()) {
      exports.run(timed("colluvium.ply", [&] { writePly(meshes.colluvium, asset_dir / "colluvium.ply"); }));
    } else {
      std::error_code ignored;  // no colluvium: no stale file from an earlier bake either
      std::filesystem::remove(asset_dir / "colluvium.ply", ignored);
    }
  }
  if (exportsFormat(preset, "obj")) exports.run(timed("obj", [&] { writeObj(meshes, asset_dir / "rock.obj"); }));
  if (exportsFormat(preset, "glb")) {
    exports.run(timed("glb", [&] { writeGlb(meshes, asset_dir / "rock.glb"); }));
    exports.run(timed("lods", [&] {
      const std::vector<AssetMeshes> lods = simplifyLods(meshes, {preset.mesh.lods});
      for (std::size_t i = 0; i < lods.size(); ++i)
        writeGlb(lods[i], asset_dir / ("rock_lod" + std::to_string(i + 1) + ".glb"));
    }));
  }
  exports.wait();  // rethrows the first failure
  r.export_seconds = export_clock.elapsed();
  return r;
}

}  // namespace rockbake
