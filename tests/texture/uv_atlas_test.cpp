// The UV atlas (texture/uv_atlas.h): on a sphere, a weathered rock and surfaces with through-
// holes, every uv lies in [0, 1], no two charts overlap and any two charts are at least
// `padding` empty texels apart, checked by rasterising the atlas; seams only split vertices.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "geometry/edge_table.h"
#include "texture/dilate_texels.h"
#include "texture/rasterize_uv.h"
#include "texture/segment_charts.h"
#include "texture/uv_atlas.h"
#include "texture_fixtures.h"

namespace rockbake {
namespace {

// Charts of an atlas: its triangles joined through shared vertices (seams split them).
std::vector<std::uint32_t> chartOfTriangles(const AssetMeshes& meshes) {
  std::vector<std::uint32_t> chart;
  std::uint32_t offset = 0;
  for (const SurfaceMesh* m : {&meshes.rock, &meshes.colluvium}) {
    std::vector<std::uint32_t> parent(m->positions.size());
    std::iota(parent.begin(), parent.end(), 0u);
    const auto find = [&](std::uint32_t v) {
      while (parent[v] != v) v = parent[v] = parent[parent[v]];
      return v;
    };
    for (const auto& t : m->triangles) {
      parent[find(t[1])] = find(t[0]);
      parent[find(t[2])] = find(t[0]);
    }
    for (const auto& t : m->triangles) chart.push_back(offset + find(t[0]));
    offset += std::uint32_t(m->positions.size());
  }
  return chart;
}

struct AtlasCheck {
  std::size_t covered = 0, contested = 0, too_close = 0;
  double within_twice_median = 0;  // share of the surface within 2x of the median texel density
};

AtlasCheck checkAtlas(const UvAtlas& atlas, const TextureParams& params) {
  const AssetMeshes& m = atlas.meshes;
  for (const SurfaceMesh* s : {&m.rock, &m.colluvium}) {
    EXPECT_EQ(s->uvs.size(), s->positions.size());
    for (const auto& uv : s->uvs) {
      EXPECT_GE(uv[0], 0.0f);
      EXPECT_LE(uv[0], 1.0f);
      EXPECT_GE(uv[1], 0.0f);
      EXPECT_LE(uv[1], 1.0f);
    }
  }
  const TexelMap texels = rasterizeUv(m, params.size);
  AtlasCheck check;
  check.covered = texels.covered;
  check.contested = texels.contested;
  // Gutters: no texel of another chart within `padding` texels (chessboard) of a covered texel.
  const std::vector<std::uint32_t> chart = chartOfTriangles(m);
  const int size = params.size, pad = params.padding;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const std::uint32_t t = texels.texels[std::size_t(y) * size + x];
      if (t == kEmptyTexel) continue;
      bool close = false;
      for (int dy = -pad; dy <= pad && !close; ++dy)
        for (int dx = -pad; dx <= pad && !close; ++dx) {
          const int nx = x + dx, ny = y + dy;
          if (nx < 0 || ny < 0 || nx >= size || ny >= size) continue;
          const std::uint32_t u = texels.texels[std::size_t(ny) * size + nx];
          close = u != kEmptyTexel && chart[u] != chart[t];
        }
      check.too_close += close;
    }
  // Texel density per triangle: sqrt(uv area / surface area), area-weighted.
  std::vector<std::pair<double, double>> density;  // (density, area)
  double total = 0;
  for (const SurfaceMesh* s : {&m.rock, &m.colluvium})
    for (const auto& t : s->triangles) {
      const auto& a = s->positions[t[0]];
      const auto& b = s->positions[t[1]];
      const auto& c = s->positions[t[2]];
      const double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
      const double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
      const double area = 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      const auto &p = s->uvs[t[0]], &q = s->uvs[t[1]], &r = s->uvs[t[2]];
      const double uv_area = 0.5 * std::abs((q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]));
      if (area <= 0) continue;
      density.push_back({std::sqrt(uv_area / area), area});
      total += area;
    }
  std::sort(density.begin(), density.end());
  double acc = 0, median = 0;
  for (const auto& [d, a] : density)
    if ((acc += a) >= 0.5 * total) {
      median = d;
      break;
    }
  double within = 0;
  for (const auto& [d, a] : density)
    if (d >= 0.5 * median && d <= 2 * median) within += a;
  check.within_twice_median = within / total;
  return check;
}

// Seams split vertices only: the same triangles, corner for corner at the same positions.
void expectSameSurface(const SurfaceMesh& before, const SurfaceMesh& after) {
  ASSERT_EQ(before.triangles.size(), after.triangles.size());
  for (std::size_t t = 0; t < before.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      ASSERT_EQ(before.positions[before.triangles[t][k]], after.positions[after.triangles[t][k]]);
      ASSERT_EQ(before.colors[before.triangles[t][k]], after.colors[after.triangles[t][k]]);
    }
}

TextureParams atlasParams(int size, int padding) {
  TextureParams p;
  p.size = size;
  p.padding = padding;
  return p;
}

TEST(UvAtlas, SphereInUnitSquareWithoutOverlapWithGutters) {
  const AssetMeshes sphere = test::assetOf(test::sphereSurface(4));
  const TextureParams params = atlasParams(512, 8);
  const UvAtlas atlas = buildUvAtlas(sphere, params.size, params.padding);
  expectSameSurface(sphere.rock, atlas.meshes.rock);
  EXPECT_GE(atlas.charts, 2u);  // a closed surface must be cut
  const AtlasCheck check = checkAtlas(atlas, params);
  EXPECT_EQ(check.contested, 0u);
  EXPECT_EQ(check.too_close, 0u);
  EXPECT_GT(double(check.covered) / (512.0 * 512.0), 0.4);
  EXPECT_GE(check.within_twice_median, 0.9);
}

TEST(UvAtlas, WeatheredRockBothSurfaces) {
  const AssetMeshes& rock = test::weatheredRock().meshes;
  ASSERT_FALSE(rock.colluvium.triangles.empty());
  const TextureParams params = atlasParams(1024, 8);
  const UvAtlas atlas = buildUvAtlas(rock, params.size, params.padding);
  expectSameSurface(rock.rock, atlas.meshes.rock);
  expectSameSurface(rock.colluvium, atlas.meshes.colluvium);
  const AtlasCheck check = checkAtlas(atlas, params);
  EXPECT_EQ(check.contested, 0u);
  EXPECT_EQ(check.too_close, 0u);
  EXPECT_GE(check.within_twice_median, 0.9);
  std::printf("weathered rock: %zu charts, %.1f %% of the map covered, %.1f %% of the surface within 2x\n",
              atlas.charts, 100.0 * double(check.covered) / (1024.0 * 1024.0), 100 * check.within_twice_median);
}

// Edges of `mesh` whose two triangles lie in different charts (`chart`: one per triangle).
std::size_t borderEdges(const SurfaceMesh& mesh, const std::vector<std::uint32_t>& chart, std::size_t offset = 0) {
  const EdgeTable edges(mesh.triangles);
  std::size_t border = 0;
  for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t)
    for (std::uint32_t k = 0; k < 3; ++k) {
      const std::uint32_t u = edges.faceAcross(3 * t + k);
      if (u != EdgeTable::kNone && u > t && chart[offset + t] != chart[offset + u]) ++border;
    }
  return border;
}

TEST(UvAtlas, FlattenedChartsMergeWhereTheUnionStillFlattensAndPacks) {
  // The segmentation's charts are split where they fail to flatten, and neighbours whose union
  // flattens with a hull no larger than theirs together are merged: on a weathered rock the
  // atlas ends with fewer charts and a shorter border (fewer seam edges, so fewer gutter
  // texels) than the segmentation drew. Flattening alone, with splits and no merges, can only
  // add charts and seams.
  const AssetMeshes& rock = test::weatheredRock().meshes;
  std::size_t segments = 0, segment_border = 0;
  for (const SurfaceMesh* m : {&rock.rock, &rock.colluvium}) {
    const std::vector<std::uint32_t> chart = segmentCharts(*m);
    if (!chart.empty()) segments += *std::max_element(chart.begin(), chart.end()) + 1;
    segment_border += borderEdges(*m, chart);
  }
  const UvAtlas atlas = buildUvAtlas(rock, 1024, 8);
  const std::vector<std::uint32_t> chart = chartOfTriangles(atlas.meshes);
  const std::size_t atlas_border =
      borderEdges(rock.rock, chart) + borderEdges(rock.colluvium, chart, rock.rock.triangles.size());
  std::printf("segmentation: %zu charts, %zu border edges; atlas: %zu charts, %zu border edges\n", segments,
              segment_border, atlas.charts, atlas_border);
  EXPECT_LT(atlas.charts, segments);
  EXPECT_LT(atlas_border, segment_border);
  const AtlasCheck check = checkAtlas(atlas, atlasParams(1024, 8));
  EXPECT_EQ(check.contested, 0u);
  EXPECT_EQ(check.too_close, 0u);
  EXPECT_GE(check.within_twice_median, 0.9);
}

TEST(UvAtlas, TorusAndArchWithThroughHoles) {
  const SurfaceMesh torus = test::torusSurface(1.0, 0.35, 48, 24);
  ASSERT_EQ(test::eulerCharacteristic(torus), 0);
  const TextureParams params = atlasParams(512, 6);
  const UvAtlas t = buildUvAtlas(test::assetOf(torus), params.size, params.padding);
  expectSameSurface(torus, t.meshes.rock);
  AtlasCheck check = checkAtlas(t, params);
  EXPECT_EQ(check.contested, 0u);
  EXPECT_EQ(check.too_close, 0u);

  const AssetMeshes& arch = test::archRock().meshes;
  // The arch stands on the ground (its rock is a capped, bent column), and its apron of debris
  // is holed through where the legs stand: a closed surface of genus > 0.
  ASSERT_LE(test::eulerCharacteristic(arch.colluvium), 0);
  const UvAtlas a = buildUvAtlas(arch, 1024, 8);
  expectSameSurface(arch.rock, a.meshes.rock);
  expectSameSurface(arch.colluvium, a.meshes.colluvium);
  check = checkAtlas(a, atlasParams(1024, 8));
  EXPECT_EQ(check.contested, 0u);
  EXPECT_EQ(check.too_close, 0u);
}

TEST(UvAtlas, ManyComponentsAndSlivers) {
  // Twenty small spheres apart, and a fan of needle-thin triangles closing a flat disk.
  SurfaceMesh many;
  for (int i = 0; i < 20; ++i) {
    const SurfaceMesh s = test::sphereSurface(1, 0.1);
    const auto base = std::uint32_t(many.positions.size());
    for (const auto& p : s.positions)
      many.positions.push_back({p[0] + 0.3f * float(i % 5), p[1] + 0.3f * float(i / 5), p[2]});
    for (const auto& t : s.triangles) many.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  }
  std::vector<std::array<float, 3>> p{{0, 0, 0}};
  std::vector<std::array<std::uint32_t, 3>> fan;
  const int spokes = 400;
  for (int i = 0; i < spokes; ++i) {
    const double a = 2 * 3.14159265358979 * i / spokes;
    p.push_back({float(std::cos(a)), float(std::sin(a)), 0.0f});
  }
  for (int i = 0; i < spokes; ++i) fan.push_back({0, std::uint32_t(1 + i), std::uint32_t(1 + (i + 1) % spokes)});
  const SurfaceMesh disk = test::surfaceOf(p, fan);
  const SurfaceMesh spheres = test::surfaceOf(many.positions, many.triangles);
  const TextureParams params = atlasParams(512, 4);
  for (const SurfaceMesh* m : {&spheres, &disk}) {
    const UvAtlas atlas = buildUvAtlas(test::assetOf(*m), params.size, params.padding);
    expectSameSurface(*m, atlas.meshes.rock);
    const AtlasCheck check = checkAtlas(atlas, params);
    EXPECT_EQ(check.contested, 0u);
    EXPECT_EQ(check.too_close, 0u);
  }
}

TEST(UvAtlas, Deterministic) {
  const AssetMeshes& rock = test::weatheredRock().meshes;
  const TextureParams params = atlasParams(512, 4);
  const UvAtlas a = buildUvAtlas(rock, params.size, params.padding),
                b = buildUvAtlas(rock, params.size, params.padding);
  EXPECT_EQ(a.meshes.rock.uvs, b.meshes.rock.uvs);
  EXPECT_EQ(a.meshes.rock.triangles, b.meshes.rock.triangles);
  EXPECT_EQ(a.texels_per_unit, b.texels_per_unit);
}

}  // namespace
}  // namespace rockbake

namespace rockbake {
namespace {

// Hidden surface (docs/textures.md, "Hidden surface"): the sphere's lower half marked hidden is
// cut from the upper half's charts and packed at a quarter of their density, so its uv area is
// about a sixteenth of the upper half's (both halves have the same surface area); without the
// marks it is of the same order (LSCM's stretch differs chart by chart). The atlas stays valid.
TEST(UvAtlas, HiddenSurfaceGetsASixteenthOfTheTexels) {
  const AssetMeshes sphere = test::assetOf(test::sphereSurface(4));
  HiddenTriangles hidden;
  const SurfaceMesh& s = sphere.rock;
  for (const auto& t : s.triangles)
    hidden[0].push_back(s.positions[t[0]][2] + s.positions[t[1]][2] + s.positions[t[2]][2] < 0 ? 1 : 0);
  const auto halves = [&](const UvAtlas& atlas) {
    std::array<double, 2> uv_area{0, 0};
    const SurfaceMesh& m = atlas.meshes.rock;
    for (std::size_t t = 0; t < m.triangles.size(); ++t) {
      const auto& a = m.uvs[m.triangles[t][0]];
      const auto& b = m.uvs[m.triangles[t][1]];
      const auto& c = m.uvs[m.triangles[t][2]];
      uv_area[hidden[0][t]] += 0.5 * std::abs((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]));
    }
    return uv_area;
  };
  const TextureParams params = atlasParams(512, 4);
  const UvAtlas plain = buildUvAtlas(sphere, params.size, params.padding);
  const UvAtlas packed = buildUvAtlas(sphere, params.size, params.padding, &hidden);
  const auto [seen0, hidden0] = halves(plain);
  const auto [seen1, hidden1] = halves(packed);
  std::printf("uv area hidden / seen: %.4f unmarked, %.4f marked\n", hidden0 / seen0, hidden1 / seen1);
  EXPECT_NEAR(hidden1 / seen1, kHiddenDensity * kHiddenDensity, 0.02);  // the halves' surface areas are equal
  EXPECT_GT(hidden0 / seen0, 0.5);
  EXPECT_GT(packed.texels_per_unit, 1.2 * plain.texels_per_unit);  // the seen half got the texels
  expectSameSurface(sphere.rock, packed.meshes.rock);
  const AtlasCheck check = checkAtlas(packed, params);
  EXPECT_EQ(check.contested, 0u);
  EXPECT_EQ(check.too_close, 0u);
}

}  // namespace
}  // namespace rockbake
