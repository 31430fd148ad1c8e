// The mesh stage's repairs on their own (docs/meshes.md, The repairs): the
// fold-over repair keeps the surface closed through many flips and collapses,
// and the repairs carry every per-vertex array (geometry/vertex_remap.h) or refuse
// one of the wrong size before changing anything.
#include <gtest/gtest.h>

#include <array>
#include <stdexcept>
#include <vector>

#include "core/hash.h"
#include "geometry/mesh_checks.h"
#include "mesh/collapsed_specks.h"
#include "mesh/fold_over_repair.h"
#include "mesh/mesh_defects.h"
#include "mesh/split_non_manifold.h"
#include "mesh/subdivide.h"

namespace rockbake {
namespace {

// Every per-vertex array but normals set from the vertex's position.
void setValuesFromPositions(SurfaceMesh& m) {
  const std::size_t n = m.positions.size();
  m.durability.resize(n), m.colluvium.resize(n), m.curvature.resize(n), m.altitude.resize(n), m.colors.resize(n);
  for (std::size_t v = 0; v < n; ++v) {
    const auto& p = m.positions[v];
    m.durability[v] = p[0], m.colluvium[v] = p[1], m.curvature[v] = p[2], m.altitude[v] = p[0] + p[1];
    m.colors[v] = {p[2], p[1], p[0]};
  }
}

// Every vertex still carries the values its position gave it.
void expectValuesFollowPositions(const SurfaceMesh& m) {
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    const auto& p = m.positions[v];
    ASSERT_EQ(m.durability[v], p[0]) << v;
    ASSERT_EQ(m.colluvium[v], p[1]) << v;
    ASSERT_EQ(m.curvature[v], p[2]) << v;
    ASSERT_EQ(m.altitude[v], p[0] + p[1]) << v;
    ASSERT_EQ(m.colors[v], (std::array<float, 3>{p[2], p[1], p[0]})) << v;
  }
}

// A closed, outward unit cube of quads refined three times by Catmull-Clark:
// a rounded box of 768 triangles, flat on z = 0.
SurfaceMesh roundedBox() {
  SurfaceMesh cube;
  cube.name = "rock";
  for (int i = 0; i < 8; ++i) cube.positions.push_back({float(i & 1), float(i >> 1 & 1), float(i >> 2 & 1)});
  cube.quads = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  SurfaceMesh m = subdivideSurface(cube, {3});
  setValuesFromPositions(m);
  return m;
}

// Vertices pulled onto a neighbour's position, or past it: zero-area
// triangles and fold-overs all over the surface, each fixed by flips and
// collapses of its own, so the repair's adjacency must follow every one.
TEST(MeshRepair, FoldOverRepairKeepsTheSurfaceClosedThroughManyFlipsAndCollapses) {
  SurfaceMesh m = roundedBox();
  ASSERT_EQ(m.triangles.size(), 768u);
  ASSERT_TRUE(checkMesh(m).clean());
  std::vector<char> moved(m.positions.size(), 0);
  for (std::uint64_t i = 0; i < 40; ++i) {
    const auto& tri = m.triangles[mix64(i) % m.triangles.size()];
    const std::uint32_t a = tri[0], b = tri[1];
    if (moved[a] || moved[b]) continue;
    const float past = i % 2 ? 1.0f : 1.3f;
    for (int k = 0; k < 3; ++k) m.positions[a][k] += past * (m.positions[b][k] - m.positions[a][k]);
    moved[a] = moved[b] = 1;
  }
  setValuesFromPositions(m);
  computeVertexNormals(m);
  const MeshDefects before = checkMesh(m);
  ASSERT_EQ(before.open_edges, 0u);
  ASSERT_GT(before.zero_area + before.fold_overs, 10u);
  const std::size_t vertices = m.positions.size();
  const double volume = signedVolume(m);

  repairFoldOvers(m);
  const MeshDefects after = checkMesh(m);
  EXPECT_EQ(after.open_edges, 0u) << "the flips and collapses left the surface open";
  EXPECT_TRUE(after.clean()) << after.zero_area << " zero-area, " << after.fold_overs << " fold-overs left";
  EXPECT_EQ(after.components, 1u);
  EXPECT_LT(m.positions.size(), vertices);  // the edges pulled to zero length were collapsed
  EXPECT_NEAR(signedVolume(m), volume, 0.05 * volume);
  expectValuesFollowPositions(m);  // no vertex moved; the collapsed ones went with all their values
  EXPECT_EQ(m.normals.size(), m.positions.size());
}

TEST(MeshRepair, SpeckRemovalCarriesEveryArray) {
  SurfaceMesh m = roundedBox();
  // A speck far away: a tetrahedron squashed flat, its faces lying on each other.
  const std::uint32_t n = std::uint32_t(m.positions.size());
  m.positions.insert(m.positions.end(), {{5, 0, 0}, {6, 0, 0}, {5.5f, 1, 0}, {5.5f, 0.3f, 1e-7f}});
  m.triangles.insert(m.triangles.end(),
                     {{n, n + 2, n + 1}, {n, n + 1, n + 3}, {n + 1, n + 2, n + 3}, {n + 2, n, n + 3}});
  setValuesFromPositions(m);
  computeVertexNormals(m);
  ASSERT_FALSE(checkMesh(m).clean());
  EXPECT_EQ(dropCollapsedSpecks(m, 24), 4u);
  EXPECT_TRUE(checkMesh(m).clean());
  EXPECT_EQ(m.positions.size(), std::size_t(n));
  EXPECT_EQ(m.normals.size(), m.positions.size());
  expectValuesFollowPositions(m);
}

// A repair that meets an array of the wrong size throws before it changes anything.
TEST(MeshRepair, AnArrayOfTheWrongSizeIsCaughtBeforeAnythingChanges) {
  SurfaceMesh m = roundedBox();
  m.positions[m.triangles[0][0]] = m.positions[m.triangles[0][1]];  // zero-area triangles to repair
  m.colors.pop_back();
  const SurfaceMesh before = m;
  const auto unchanged = [&] { return m.positions == before.positions && m.triangles == before.triangles; };
  EXPECT_THROW(repairFoldOvers(m), std::logic_error);
  EXPECT_TRUE(unchanged());
  EXPECT_THROW(dropCollapsedSpecks(m, 10000), std::logic_error);
  EXPECT_TRUE(unchanged());
  EXPECT_THROW(splitNonManifold(m), std::logic_error);
  EXPECT_TRUE(unchanged());
}

}  // namespace
}  // namespace rockbake
