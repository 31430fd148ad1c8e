// The mesh stage at a hero resolution (docs/meshes.md, Subdivision serves coarse
// grids): how many levels are spent, and a rock at 256 meshed without
// subdivision, LOD0 simplified from the extraction directly: within its bound
// of the bake source, closed, faithful to the voxels, and a clean LOD chain.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_map>
#include <vector>

#include "core/vec3.h"
#include "inputs/resolve_shape.h"
#include "mesh/mesh_defects.h"
#include "mesh/refinement_levels.h"
#include "mesh/simplify_lods.h"
#include "pipeline/bake_meshes.h"
#include "sim/shapes.h"
#include "test_support.h"

namespace rockbake {
namespace {

// ---- how many levels ----

TEST(MeshRefinementLevels, SpentOnlyWhileTheVoxelsAreTooCoarseForTheDetail) {
  const NoiseParams house{0.01, 0.08, 3};  // presets/base.yaml: grains of 0.08
  // goblin at 96 (voxels of 0.0625) keeps its level; at 384 (0.0156) spends none.
  EXPECT_EQ(refinementLevels(1, 6.0 / 96, house), 1);
  EXPECT_EQ(refinementLevels(1, 6.0 / 384, house), 0);
  // Edges of 0.0625 need two halvings to reach 0.02, when the preset allows them.
  EXPECT_EQ(refinementLevels(3, 6.0 / 96, house), 2);
  EXPECT_EQ(refinementLevels(3, 0.02, house), 0);    // a quarter period exactly: fine enough
  EXPECT_EQ(refinementLevels(3, 0.0201, house), 1);  // just coarser: one level
  EXPECT_EQ(refinementLevels(0, 1.0, house), 0);     // never more than the preset asks
  // Without detail nothing is measured in world units: the preset's levels.
  EXPECT_EQ(refinementLevels(2, 6.0 / 384, std::nullopt), 2);
  EXPECT_EQ(refinementLevels(2, 6.0 / 384, NoiseParams{0.0, 0.08, 3}), 2);
}

// Every shipped preset at its own resolution keeps the level base.yaml gives it:
// the house bake does not change.
TEST(MeshRefinementLevels, EveryShippedPresetKeepsItsLevelAtItsResolution) {
  const NoiseParams house{0.01, 0.08, 3};
  // The finest voxels of the catalogue: rounded-cobble, 3.2 across at 96.
  EXPECT_EQ(refinementLevels(1, 3.2 / 96, house), 1);
}

// ---- a rock at 256 ----

// A lumpy rock resting on the ground, a boulder apart from it and an apron of
// colluvium around its foot, 256 voxels across (voxels of 0.0078: the house
// detail's grains are ten voxels wide, so no level is spent).
Preset heroPreset() {
  Preset p = test::cubePreset(2.0, 256, 0.2);
  p.name = "hero";
  p.grid.size = {2.0, 2.0, 0.9};
  p.grid.ground = true;
  p.shape.kind = BoxShape{{1.0, 1.0, 0.5}};  // replaced voxel by voxel below
  p.mesh.smoothing = 1.0;
  p.mesh.subdivision = 1;
  p.mesh.max_error = 0.15;
  p.mesh.detail = NoiseParams{0.01, 0.08, 3};
  p.mesh.lods = {20000, 5000, 1200, 300};
  return p;
}

const VoxelRock& heroRock() {
  static const VoxelRock rock = [] {
    const Preset p = heroPreset();
    VoxelRock r = buildInitialRock(resolveShape(p), p);
    const GridLayout& g = r.layout;
    for (int z = 0; z < g.nz; ++z)
      for (int y = 0; y < g.ny; ++y)
        for (int x = 0; x < g.nx; ++x) {
          const double px = (x + 0.5) * g.h, py = (y + 0.5) * g.h, pz = (z + 0.5) * g.h;
          const double lump = 1.0 + 0.12 * std::sin(9 * px) * std::sin(7 * py) * std::sin(11 * pz);
          const double dx = (px - 0.95) / 0.6, dy = (py - 1.0) / 0.45, dz = (pz - 0.2) / 0.6;
          const bool rock = dx * dx + dy * dy + dz * dz < lump * lump;
          const double bx = px - 1.72, by = py - 1.72, bz = pz - 0.1;
          const bool boulder = bx * bx + by * by + bz * bz < 0.12 * 0.12;
          const bool apron = pz < 0.05 && dx * dx + dy * dy < 1.35 * 1.35;
          const std::size_t i = g.index(x, y, z);
          r.material[i] = rock || boulder ? Material::Rock : apron ? Material::Colluvium : Material::Air;
          if (r.material[i] == Material::Rock) r.durability.set(i, float(1.0 + 0.5 * std::sin(3 * pz)));
        }
    return r;
  }();
  return rock;
}

std::size_t count(const VoxelRock& rock, Material m) {
  return std::size_t(std::count(rock.material.begin(), rock.material.end(), m));
}

// The point of triangle abc nearest p (Ericson, Real-Time Collision Detection, §5.1.5).
Vec3d closestOnTriangle(const Vec3d& p, const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  const Vec3d ab = sub(b, a), ac = sub(c, a), ap = sub(p, a);
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vec3d bp = sub(p, b);
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return add(a, scale(ab, d1 / (d1 - d3)));
  const Vec3d cp = sub(p, c);
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return add(a, scale(ac, d2 / (d2 - d6)));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) return add(b, scale(sub(c, b), (d4 - d3) / ((d4 - d3) + (d5 - d6))));
  const double denom = 1.0 / (va + vb + vc);
  return add(a, add(scale(ab, vb * denom), scale(ac, vc * denom)));
}

// The largest distance from a vertex of `from` to the surface `to` (world
// units): triangles bucketed in a grid of cells `cell` wide by their bounding
// boxes; a vertex searches the cells within `reach` of it (and counts `reach`
// when it finds nothing nearer).
double largestDistance(const SurfaceMesh& from, const SurfaceMesh& to, double cell, double reach) {
  const auto key = [&](std::int64_t x, std::int64_t y, std::int64_t z) {
    return std::uint64_t(x * 73856093) ^ std::uint64_t(y * 19349663) ^ std::uint64_t(z * 83492791);
  };
  const auto index = [&](double v) { return std::int64_t(std::floor(v / cell)); };
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> grid;
  for (std::uint32_t t = 0; t < to.triangles.size(); ++t) {
    std::array<std::int64_t, 3> lo{}, hi{};
    for (int a = 0; a < 3; ++a) {
      double mn = 1e30, mx = -1e30;
      for (std::uint32_t v : to.triangles[t])
        mn = std::min(mn, double(to.positions[v][a])), mx = std::max(mx, double(to.positions[v][a]));
      lo[a] = index(mn), hi[a] = index(mx);
    }
    for (auto x = lo[0]; x <= hi[0]; ++x)
      for (auto y = lo[1]; y <= hi[1]; ++y)
        for (auto z = lo[2]; z <= hi[2]; ++z) grid[key(x, y, z)].push_back(t);
  }
  const std::int64_t r = std::int64_t(std::ceil(reach / cell));
  double largest = 0;
  for (const auto& q : from.positions) {
    const Vec3d p = toVec3d(q);
    double best = reach * reach;
    for (auto x = index(p[0]) - r; x <= index(p[0]) + r; ++x)
      for (auto y = index(p[1]) - r; y <= index(p[1]) + r; ++y)
        for (auto z = index(p[2]) - r; z <= index(p[2]) + r; ++z) {
          const auto it = grid.find(key(x, y, z));
          if (it == grid.end()) continue;
          for (std::uint32_t t : it->second) {
            const auto& tri = to.triangles[t];
            const Vec3d c = closestOnTriangle(p, toVec3d(to.positions[tri[0]]), toVec3d(to.positions[tri[1]]),
                                              toVec3d(to.positions[tri[2]]));
            best = std::min(best, distanceSquared(p, c));
          }
        }
    largest = std::max(largest, std::sqrt(best));
  }
  return largest;
}

const MeshStageResult& heroMeshes() {
  static const MeshStageResult r = buildMeshes(heroRock(), heroPreset(), /*keep_bake_source=*/true);
  return r;
}

TEST(MeshHero, SimplifiesFromTheExtractionWithoutSubdivision) {
  const MeshStageResult& r = heroMeshes();
  EXPECT_EQ(r.subdivision_levels, 0);
  const AssetMeshes& source = r.bake_source;
  ASSERT_GT(source.rock.triangles.size(), 100000u);
  EXPECT_EQ(source.rock.triangles.size() + source.colluvium.triangles.size(), r.refined_triangles);
  EXPECT_TRUE(source.rock.quads.empty());
  EXPECT_EQ(source.rock.colors.size(), source.rock.positions.size());
  const std::size_t lod0 = r.meshes.rock.triangles.size() + r.meshes.colluvium.triangles.size();
  EXPECT_LT(4 * lod0, r.refined_triangles);
  // Without asking, no bake source is kept.
  const Preset small = test::cubePreset(2.0, 24, 0.2);
  const VoxelRock box = buildInitialRock(resolveShape(small), small);
  EXPECT_TRUE(buildMeshes(box, small).bake_source.rock.positions.empty());
  EXPECT_FALSE(buildMeshes(box, small, true).bake_source.rock.positions.empty());
}

// LOD0's vertices are the bake source's own (the simplifier only removes
// vertices), so each lies on the surface it was simplified from; the other way
// round, meshoptimizer's error is its quadric estimate, not a distance bound,
// and the source's vertices lie up to about three times max_error from LOD0
// (on this rock 0.42 voxels for the rock, 0.28 for the colluvium; through one
// level of subdivision, as at the house resolution, 0.45 and 0.35). The apron's
// toe (mesh.apron_toe) ends in a wedge thinner than the bound, whose tip the
// simplifier may take back by more: 0.61 voxels on this rock's colluvium, so
// the colluvium is held to five times the bound.
TEST(MeshHero, Lod0IsWithinItsBoundOfTheBakeSource) {
  const MeshStageResult& r = heroMeshes();
  const double h = heroRock().layout.h, bound = heroPreset().mesh.max_error * h;
  for (const auto& [lod0, source] :
       {std::pair{&r.meshes.rock, &r.bake_source.rock}, std::pair{&r.meshes.colluvium, &r.bake_source.colluvium}}) {
    ASSERT_FALSE(lod0->triangles.empty()) << lod0->name;
    std::vector<std::array<float, 3>> kept = source->positions;
    std::sort(kept.begin(), kept.end());
    for (const auto& p : lod0->positions)
      ASSERT_TRUE(std::binary_search(kept.begin(), kept.end(), p)) << lod0->name << ": a vertex not of the source";
    const double largest = largestDistance(*source, *lod0, 4 * h, 2 * h);
    EXPECT_LE(largest, (lod0->name == "colluvium" ? 5 : 3) * bound) << lod0->name << ": " << largest / h << " voxels";
  }
}

TEST(MeshHero, Lod0IsClosedAndFaithfulToTheVoxels) {
  const MeshStageResult& r = heroMeshes();
  const VoxelRock& rock = heroRock();
  const double voxel = std::pow(rock.layout.h, 3);
  for (const auto& [mesh, material] :
       {std::pair{&r.meshes.rock, Material::Rock}, std::pair{&r.meshes.colluvium, Material::Colluvium}}) {
    const MeshDefects d = checkMesh(*mesh);
    EXPECT_TRUE(d.clean()) << mesh->name << ": " << d.open_edges << " open edges, " << d.fold_overs << " fold-overs, "
                           << d.zero_area << " zero-area";
    const double voxels = double(count(rock, material)) * voxel;
    EXPECT_NEAR(d.volume / voxels, 1.0, 0.03) << mesh->name;
    EXPECT_LE(d.shells, test::voxelComponents(rock, material)) << mesh->name;
    EXPECT_GE(d.shells, 1u) << mesh->name;
  }
  EXPECT_EQ(test::voxelComponents(rock, Material::Rock), 2u);  // the rock and the boulder
  EXPECT_EQ(checkMesh(r.meshes.rock).shells, 2u);
}

TEST(MeshHero, TheLodChainKeepsItsBudgetsWithoutFoldOvers) {
  const MeshStageResult& r = heroMeshes();
  const std::vector<double> counts = heroPreset().mesh.lods;
  const std::vector<AssetMeshes> lods = simplifyLods(r.meshes, {counts});
  ASSERT_EQ(lods.size(), counts.size());
  for (std::size_t i = 0; i < lods.size(); ++i) {
    const double total = double(lods[i].rock.triangles.size() + lods[i].colluvium.triangles.size());
    EXPECT_NEAR(total / counts[i], 1.0, 0.1) << "LOD" << i + 1;
    for (const SurfaceMesh* m : {&lods[i].rock, &lods[i].colluvium}) {
      const MeshDefects d = checkMesh(*m);
      EXPECT_TRUE(d.clean()) << m->name << " LOD" << i + 1 << ": " << d.open_edges << " open edges, " << d.fold_overs
                             << " fold-overs, " << d.zero_area << " zero-area";
    }
  }
}

}  // namespace
}  // namespace rockbake
