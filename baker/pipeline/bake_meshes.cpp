#include "pipeline/bake_meshes.h"

#include "geometry/mesh_checks.h"
#include "platform/side_by_side.h"
#include "platform/stopwatch.h"

#include <algorithm>
#include <chrono>
#include <limits>
#include <string>

#include <spdlog/spdlog.h>

#include "mesh/apron_toe.h"
#include "mesh/bake_attributes.h"
#include "mesh/extract_surfaces.h"
#include "mesh/fold_over_repair.h"
#include "mesh/refinement_levels.h"
#include "mesh/relax_fold_overs.h"
#include "mesh/simplify_lods.h"
#include "mesh/subdivide.h"
#include "mesh/surface_detail.h"
#include "mesh/surface_look.h"
#include "sim/durability.h"
#include "sim/family.h"
#include "sim/weathering.h"

namespace rockbake {

namespace {

// The surface detail of mesh.detail and the look's processes (mesh/surface_detail.h): the laminae
// lie along the simulation's own beds.
void displaceRock(SurfaceMesh& rock_mesh, const VoxelRock& rock, const Preset& preset, const PaletteParams& palette) {
  DetailParams detail{preset.mesh.detail.value_or(NoiseParams{0.0, 1.0, 1}),
                      preset.seed,
                      palette.durability_min,
                      palette.durability_max,
                      rock.layout.ground,
                      {}};
  std::optional<Geology> geology;
  if (preset.look) {
    detail.processes.laminations = preset.look->laminations;
    detail.processes.exfoliation = preset.look->exfoliation;
    detail.processes.pitting = preset.look->pitting;
    detail.processes.retreat = std::max(rock.history.cycles, 1) * rock.layout.h;
    const Vec3d domain = simulationDomain(preset);
    geology.emplace(individualDurability(preset), domain, preset.seed);
    detail.processes.bed_position = [&geology, height = domain[2]](const Vec3d& p) {
      return geology->bedAltitude(p) * height;
    };
  }
  if (detail.noise.amplitude > 0 || detail.processes.any()) displaceSurface(rock_mesh, detail);
}

}  // namespace

bool exportsFormat(const Preset& preset, const std::string& format) {
  return std::find(preset.exports.begin(), preset.exports.end(), format) != preset.exports.end();
}

MeshStageResult buildMeshes(const VoxelRock& rock, const Preset& preset, bool keep_bake_source,
                            const std::vector<BubbleBand>* bubbles) {
  MeshStageResult r;
  Stopwatch clock;
  AssetMeshes meshes = extractSurfaces(rock, {preset.mesh.smoothing}, &r.rock_sdf);
  r.times.add("extract", clock.lap());

  const std::vector<float> exposure = exposureField(rock, bubbles ? *bubbles : preset.bubbles);
  meshes = sampleAttributes(std::move(meshes), {&rock, &exposure, preset.look.has_value()});
  r.times.add("attributes", clock.lap());

  const GridLayout& g = rock.layout;
  // Subdivision serves coarse grids only: a level is spent while the voxels are
  // too coarse to carry the detail (mesh/refinement_levels.h).
  r.subdivision_levels = refinementLevels(preset.mesh.subdivision, g.h, preset.mesh.detail);
  const SubdivideParams levels{r.subdivision_levels};
  // The two surfaces are refined side by side (each step reads its own surface and field only).
  const double voxel = g.h * g.h * g.h;
  sideBySide(
      [&] {
        meshes.rock = subdivideSurface(meshes.rock, levels);
        // Catmull-Clark pulls the surface inside the field it was extracted from: put
        // it back on it. Then give back the voxels' volume smoothing rounded off.
        projectOntoField(meshes.rock, r.rock_sdf.get(), g.ground);
        const double delta = matchVolume(meshes.rock, double(rock.count(Material::Rock)) * voxel, 0.5 * g.h, g.ground);
        r.rock_sdf = offsetField(r.rock_sdf, delta, g.ground);
        // The shift along vertex normals and the field's shift agree only where its
        // gradient has unit length: settle the vertices on the field rock.vdb keeps.
        projectOntoField(meshes.rock, r.rock_sdf.get(), g.ground);
        // Where the field is creased (a voxel-thin part), projected neighbours can
        // land folded over each other: flip those edges back (no vertex moves).
        repairFoldOvers(meshes.rock);
      },
      [&] {
        meshes.colluvium = subdivideSurface(meshes.colluvium, levels);
        matchVolume(meshes.colluvium, double(rock.count(Material::Colluvium)) * voxel, 0.5 * g.h, g.ground);
        repairFoldOvers(meshes.colluvium);
      });
  // The apron thins out onto the ground along a toe, instead of ending in the voxels' rounded lip.
  if (preset.mesh.apron_toe > 0) {
    updateBounds(meshes);
    shapeApronToe(meshes, g, {preset.mesh.apron_toe});
    // Where the spread pushed a vertex past its neighbours (at the rim's inward corners), flip the
    // edges back, then relax what flipping cannot mend (mesh/relax_fold_overs.h).
    repairFoldOvers(meshes.colluvium);
    relaxFoldOvers(meshes.colluvium);
  }
  r.times.add("subdivide", clock.lap());

  PaletteParams palette = paletteParams(rock, preset.bake);
  displaceRock(meshes.rock, rock, preset, palette);
  if (preset.look) {
    const LookParams& look = *preset.look;
    makeSurfaceLook(meshes, {look.stain, look.varnish, look.moisture, look.dust, &rock});
    palette.look = look;
    palette.seed = preset.seed;
    palette.voxel = g.h;
  }
  updateBounds(meshes);
  meshes.durability_range = {palette.durability_min, palette.durability_max};
  meshes = applyPalette(std::move(meshes), palette);
  r.pivot = footprintPivot(rock, sinkDepth(rock, preset.mesh.sink));
  movePivot(meshes, r.pivot);
  r.times.add("attributes", clock.lap());

  r.refined_triangles = meshes.rock.triangles.size() + meshes.colluvium.triangles.size();
  SimplifyWarnings warnings;
  r.meshes = simplifyToError(meshes, preset.mesh.max_error * g.h, &warnings);
  for (const std::string& w : warnings) spdlog::warn("{}: {}", preset.name, w);  // in a library, the job's name
  if (keep_bake_source) r.bake_source = std::move(meshes);
  r.times.add("simplify", clock.lap());
  spdlog::debug(
      "{}: {} subdivision level(s), refined {} triangles; LOD0 rock {} vertices, {} triangles; colluvium {} vertices, "
      "{} triangles",
      preset.name, r.subdivision_levels, r.refined_triangles, r.meshes.rock.positions.size(),
      r.meshes.rock.triangles.size(), r.meshes.colluvium.positions.size(), r.meshes.colluvium.triangles.size());
  return r;
}

void addLods(MeshStageResult& r, const Preset& preset, const std::vector<double>& targets) {
  if (exportsFormat(preset, "glb")) {
    Stopwatch clock;
    SimplifyWarnings warnings;
    r.lods = simplifyLods(r.meshes, {targets}, &warnings);
    for (const std::string& w : warnings) spdlog::warn("{}: {}", preset.name, w);
    r.times.add("simplify", clock.lap());
  }
  r.lod_files.clear();
  r.lod_files.push_back(exportsFormat(preset, "glb") ? "rock.glb" : exportsFormat(preset, "ply") ? "rock.ply" : "");
  for (std::size_t i = 0; i < r.lods.size(); ++i) r.lod_files.push_back("rock_lod" + std::to_string(i + 1) + ".glb");
}

std::vector<std::size_t> lodBudgets(const Preset& preset, std::size_t lod0_triangles) {
  std::vector<std::size_t> budgets;
  for (const double t : preset.mesh.lods)
    budgets.push_back(t < 1.0 ? std::size_t(std::llround(t * double(lod0_triangles))) : std::size_t(t));
  return budgets;
}

MeshStageResult bakeMeshes(const VoxelRock& rock, const Preset& preset, bool keep_bake_source) {
  MeshStageResult r = buildMeshes(rock, preset, keep_bake_source);
  addLods(r, preset, preset.mesh.lods);
  return r;
}

}  // namespace rockbake
