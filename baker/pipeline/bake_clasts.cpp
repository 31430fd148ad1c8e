#include "pipeline/bake_clasts.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "clasts/clast_blocks.h"
#include "clasts/place_clasts.h"
#include "core/hash.h"
#include "geometry/mesh_checks.h"
#include "geometry/vertex_remap.h"
#include "mesh/bake_attributes.h"
#include "sim/grid_layout.h"
#include "sim/weathering.h"
#include "texture/texture_set.h"

namespace rockbake {
namespace {

constexpr int kShapeResolution = 24;  // voxels across a stone's small grid

// The durability of a seeded rock voxel: the layer stone `index` fell from.
float parentDurability(const VoxelRock& rock, std::uint64_t seed, int index) {
  const std::size_t cells = rock.layout.cellCount();
  for (std::uint64_t attempt = 0; attempt < 4096; ++attempt) {
    const std::size_t c =
        std::size_t(counterHash(seed, purposeId("clast parent"), std::uint64_t(index), attempt) % cells);
    if (rock.material[c] == Material::Rock) return rock.durability[c];
  }
  for (std::size_t c = 0; c < cells; ++c)
    if (rock.material[c] == Material::Rock) return rock.durability[c];
  return 1.0f;
}

// The small simulation a stone weathers in: a free-floating block, no rockfall or debris, one
// spheroidal band (a bubble a fifth of the stone across rounds its edges and corners).
SimParams stoneSimulation(const Preset& preset, int index, double length) {
  SimParams p;
  p.seed = counterHash(preset.seed, purposeId("clast simulation"), std::uint64_t(index), 0);
  p.grid.size = {1.3 * length, 1.3 * length, 1.3 * length};
  p.grid.resolution = kShapeResolution;
  p.grid.ground = false;
  p.shape.kind = BoxShape{{length, length, length}};  // not read: the block is given as voxels
  BubbleBand band;
  band.bubble.kind = BubbleSpec::Kind::Sphere;
  band.bubble.extents = {0.2 * length, 0.0, 0.0};
  band.spheroidal = 1.0;
  band.cavernous = 0.0;
  p.bubbles = {band};
  p.response = preset.response;
  p.rockfall.mode = RockfallMode::Off;
  p.colluvium.yield = 0.0;
  p.stop.cycles = 2 + index % 4;  // fresh, angular stones beside well-rounded ones
  return p;
}

// Moves and scales `m` by (p - centre) / extent.
void normalise(SurfaceMesh& m, const Vec3d& centre, double extent) {
  for (auto& p : m.positions)
    for (int a = 0; a < 3; ++a) p[a] = float((p[a] - centre[a]) / extent);
}

// One stone mesh and its finest surface, longest axis 1, centred on its bounding box.
void makeShape(const VoxelRock& parent, const Preset& preset, const PaletteParams& palette, int index,
               SurfaceMesh& shape, SurfaceMesh& source) {
  const double length = preset.clasts->size[1] * parent.layout.h;
  const SimParams sp = stoneSimulation(preset, index, length);
  const GridLayout layout = computeGridLayout(sp);
  WeatheringSimulation simulation(voxelizeClastBlock(drawClastBlock(preset.seed, index, length), layout, 1.0f), sp);
  while (!simulation.finished()) simulation.step();
  VoxelRock stone = simulation.release();
  const float durability = parentDurability(parent, preset.seed, index);
  for (std::size_t c = 0; c < stone.material.size(); ++c)
    if (stone.material[c] == Material::Rock) stone.durability.set(c, durability);

  Preset meshing = preset;
  static_cast<SimParams&>(meshing) = sp;
  meshing.mesh.lods = {double(kClastShapeTriangles)};
  meshing.exports = {"glb"};
  // A stone's few cycles leave no history to speak of, and the look's lengths are the asset's:
  // stones keep the palette's look (docs/model.md §13).
  meshing.look.reset();
  MeshStageResult r = bakeMeshes(stone, meshing, true);
  AssetMeshes lod = applyPalette(std::move(r.lods.at(0)), palette);
  AssetMeshes fine = applyPalette(std::move(r.bake_source), palette);
  updateBounds(lod);
  Vec3d centre{}, extent{};
  for (int a = 0; a < 3; ++a) {
    centre[a] = 0.5 * (double(lod.bounds_min[a]) + lod.bounds_max[a]);
    extent[a] = double(lod.bounds_max[a]) - lod.bounds_min[a];
  }
  const double longest = std::max({extent[0], extent[1], extent[2], 1e-9});
  shape = std::move(lod.rock);
  source = std::move(fine.rock);
  normalise(shape, centre, longest);
  normalise(source, centre, longest);
  shape.name = source.name = "clast";
}

// Shape k moved kSpacing × k along x, so that the shapes baked together never see each other.
constexpr double kSpacing = 2.0;

SurfaceMesh laidInARow(const std::vector<SurfaceMesh>& shapes) {
  SurfaceMesh row;
  row.name = "clast";
  for (std::size_t k = 0; k < shapes.size(); ++k) {
    const SurfaceMesh& m = shapes[k];
    const auto base = std::uint32_t(row.positions.size());
    std::apply(
        [&](const auto&... array) {
          ((row.*(array.member))
               .insert((row.*(array.member)).end(), (m.*(array.member)).begin(), (m.*(array.member)).end()),
           ...);
        },
        kVertexArrays);
    for (std::size_t v = base; v < row.positions.size(); ++v) row.positions[v][0] += float(kSpacing * double(k));
    for (const auto& t : m.triangles) row.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  }
  return row;
}

// The inverse of laidInARow on an unwrapped row: each shape's triangles (by where they lie) with
// the vertices they use, in order of first use, moved back.
std::vector<SurfaceMesh> splitRow(const SurfaceMesh& row, std::size_t shapes) {
  std::vector<std::vector<std::uint32_t>> source(shapes);
  std::vector<std::vector<std::uint32_t>> index(shapes,
                                                std::vector<std::uint32_t>(row.positions.size(), kDroppedVertex));
  std::vector<std::vector<std::array<std::uint32_t, 3>>> triangles(shapes);
  for (const auto& t : row.triangles) {
    const double x = (double(row.positions[t[0]][0]) + row.positions[t[1]][0] + row.positions[t[2]][0]) / 3.0;
    const std::size_t k = std::size_t(std::clamp(std::lround(x / kSpacing), 0L, long(shapes) - 1));
    std::array<std::uint32_t, 3> local{};
    for (int c = 0; c < 3; ++c) {
      std::uint32_t& at = index[k][t[c]];
      if (at == kDroppedVertex) at = std::uint32_t(source[k].size()), source[k].push_back(t[c]);
      local[c] = at;
    }
    triangles[k].push_back(local);
  }
  std::vector<SurfaceMesh> out(shapes);
  for (std::size_t k = 0; k < shapes; ++k) {
    out[k] = gatherVertices(row, source[k]);
    out[k].triangles = std::move(triangles[k]);
    for (auto& p : out[k].positions) p[0] = float(p[0] - kSpacing * double(k));
  }
  return out;
}

}  // namespace

ClastStage bakeClasts(const VoxelRock& rock, const MeshStageResult& meshes, const Preset& preset) {
  ClastStage stage;
  if (!preset.clasts || !rock.layout.ground || meshes.meshes.colluvium.triangles.empty()) return stage;
  const PaletteParams palette = paletteParams(rock, preset.bake);
  stage.set.shapes.resize(std::size_t(preset.clasts->shapes));
  stage.sources.resize(stage.set.shapes.size());
  for (std::size_t k = 0; k < stage.set.shapes.size(); ++k)
    makeShape(rock, preset, palette, int(k), stage.set.shapes[k], stage.sources[k]);
  ClastPlacement placement;
  placement.rock = &rock;
  placement.pivot = meshes.pivot;
  placement.colluvium = &meshes.meshes.colluvium;
  placement.shapes = &stage.set.shapes;
  placement.params = *preset.clasts;
  placement.seed = preset.seed;
  stage.set.stones = placeClasts(placement);
  stage.set.lod_counts = {stage.set.stones.size()};
  return stage;
}

std::vector<std::size_t> clastLodCounts(const ClastSet& set, const std::vector<std::size_t>& budgets) {
  std::vector<std::size_t> counts{set.stones.size()};
  for (std::size_t k = 0; k < budgets.size(); ++k) {
    std::size_t n = 0, triangles = 0;
    if (k + 1 < budgets.size())
      for (; n < set.stones.size(); ++n) {
        triangles += set.shapes.at(std::size_t(set.stones[n].shape)).triangles.size();
        if (double(triangles) > kClastLodShare * double(budgets[k])) break;
      }
    counts.push_back(n);
  }
  return counts;
}

void textureClasts(ClastStage& stage, const Preset& preset, const std::filesystem::path& folder,
                   const std::string& name, bool directx_normals) {
  ClastSet& set = stage.set;
  if (set.shapes.empty() || set.stones.empty() || !preset.texture) return;
  AssetMeshes lod, source;
  lod.rock = laidInARow(set.shapes);
  source.rock = laidInARow(stage.sources);
  updateBounds(lod);
  updateBounds(source);
  TextureSetRequest request;
  request.params = *preset.texture;
  request.params.size = std::clamp(preset.texture->size / 4, 256, 1024);
  request.params.maps = {TextureMap::BaseColor, TextureMap::Normal, TextureMap::Orm};
  request.params.lod_size = LodMapSize::Full;
  request.params.colour_density = 0;  // a stone's maps are small already, and its voxels are not the rock's
  // In shape units (longest axis 1): the source lies within a voxel of the small grid, and no
  // occlusion ray reaches the next shape of the row (at least 1 away).
  request.params.cage = 0.05;
  request.params.ao_distance = 0.5;
  request.seed = counterHash(preset.seed, purposeId("clast maps"), 0, 0);
  request.voxel_size = 1.3 / kShapeResolution;
  request.varied = preset.bake.palette == Palette::Natural;
  request.name = name + "_Clasts";
  request.directx_normals = directx_normals;
  request.folder = folder;
  const TextureSet maps = bakeTextureSet({lod}, source, request);
  set.shapes = splitRow(maps.lods.at(0).rock, set.shapes.size());
  const auto file = [&](TextureMap m) {
    const TextureFile* f = findTextureFile(maps, 0, m);
    return f ? f->file : std::string();
  };
  set.base_color = file(TextureMap::BaseColor);
  set.normal = file(TextureMap::Normal);
  set.orm = file(TextureMap::Orm);
  set.map_size = maps.sizes.at(0);
}

}  // namespace rockbake
