// The mesh kernel's vertex remap (geometry/vertex_remap.h; docs/mesh-kernel.md):
// every per-vertex array of SurfaceMesh (kVertexArrays) carried through
// gathering, compaction, welding and splitting, and one contract for arrays of
// the wrong size.
#include <gtest/gtest.h>

#include <array>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

#include "geometry/vertex_remap.h"
#include "mesh_fixtures.h"

namespace rockbake {
namespace {

// The value array `k` (its place in kVertexArrays) holds for vertex v: distinct everywhere.
float tag(std::size_t k, std::uint32_t v) {
  return float(1000 * (k + 1) + v);
}
void setTag(float& value, std::size_t k, std::uint32_t v) {
  value = tag(k, v);
}
// Arrays of any width: component c holds tag + c, so a swapped component shows.
template <std::size_t N>
void setTag(std::array<float, N>& value, std::size_t k, std::uint32_t v) {
  for (std::size_t c = 0; c < N; ++c) value[c] = tag(k, v) + float(c) / 8;
}
bool hasTag(float value, std::size_t k, std::uint32_t v) {
  return value == tag(k, v);
}
template <std::size_t N>
bool hasTag(const std::array<float, N>& value, std::size_t k, std::uint32_t v) {
  std::array<float, N> expected;
  setTag(expected, k, v);
  return value == expected;
}

// Every per-vertex array filled, each value naming its array and vertex;
// positions keep the geometry.
SurfaceMesh tagged(SurfaceMesh m) {
  const std::size_t n = m.positions.size();
  std::size_t k = 0;
  forEachVertexArray(m, [&](const char* name, auto& values) {
    if (std::string(name) != "positions") {
      values.resize(n);
      for (std::uint32_t v = 0; v < n; ++v) setTag(values[v], k, v);
    }
    ++k;
  });
  return m;
}

// Every array but positions of `out` holds, at vertex i, what `in` held at source[i].
void expectCarried(const SurfaceMesh& in, const SurfaceMesh& out, const std::vector<std::uint32_t>& source) {
  std::size_t k = 0, arrays = 0;
  forEachVertexArray(out, [&](const char* name, const auto& values) {
    ++arrays;
    ASSERT_EQ(values.size(), source.size()) << name;
    for (std::uint32_t i = 0; i < source.size(); ++i) {
      if (std::string(name) == "positions")
        EXPECT_EQ(out.positions[i], in.positions[source[i]]) << i;
      else
        EXPECT_TRUE(hasTag(values[i], k, source[i])) << name << " at vertex " << i;
    }
    ++k;
  });
  EXPECT_EQ(arrays, std::tuple_size_v<decltype(kVertexArrays)>);
}

TEST(VertexRemap, EveryArrayIsListedOnceWithItsName) {
  SurfaceMesh m;
  std::vector<std::string> names;
  forEachVertexArray(m, [&](const char* name, const auto&) { names.push_back(name); });
  EXPECT_EQ(names, (std::vector<std::string>{"positions", "normals", "durability", "colluvium", "curvature", "altitude",
                                             "colors", "history", "look", "uvs", "tangents"}));
}

TEST(VertexRemap, GatherCarriesEveryArray) {
  const SurfaceMesh cube = tagged(test::unitCube());
  const std::vector<std::uint32_t> source{7, 0, 0, 3, 5};  // reordered, repeated, some left out
  const SurfaceMesh out = gatherVertices(cube, source);
  EXPECT_EQ(out.name, cube.name);
  EXPECT_TRUE(out.triangles.empty());
  expectCarried(cube, out, source);
}

TEST(VertexRemap, EmptyArraysStayEmpty) {
  SurfaceMesh cube = test::unitCube();  // positions only
  appendVertexCopies(cube, std::vector<std::uint32_t>{2});
  EXPECT_EQ(cube.positions.size(), 9u);
  EXPECT_EQ(cube.positions[8], cube.positions[2]);
  EXPECT_TRUE(cube.normals.empty());
  EXPECT_TRUE(cube.colors.empty());
}

TEST(VertexRemap, CompactionDropsUnusedVerticesAndKeepsTheGeometry) {
  // The tetrahedron with an unused vertex before, between and after its own.
  test::MeshBuilder b;
  b.vertex({9, 9, 9});
  const SurfaceMesh tet = test::tetrahedron();
  for (std::size_t i = 0; i < tet.triangles.size(); ++i) {
    const auto& t = tet.triangles[i];
    b.vertex({8, 8, float(i)});
    b.triangle(tet.positions[t[0]], tet.positions[t[1]], tet.positions[t[2]]);
  }
  b.vertex({7, 7, 7});
  const SurfaceMesh in = tagged(b.mesh());
  SurfaceMesh m = in;
  ASSERT_EQ(m.positions.size(), 4u + 6u);
  EXPECT_EQ(compactVertices(m), 6u);
  std::vector<std::uint32_t> kept;
  for (std::uint32_t v = 0; v < in.positions.size(); ++v)
    if (in.positions[v][0] < 2) kept.push_back(v);
  expectCarried(in, m, kept);
  ASSERT_EQ(m.triangles.size(), in.triangles.size());
  for (std::size_t t = 0; t < m.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) EXPECT_EQ(m.positions[m.triangles[t][k]], in.positions[in.triangles[t][k]]);
}

TEST(VertexRemap, CompactMeshDropsCollapsedTriangles) {
  SurfaceMesh m = tagged(test::tetrahedron());
  m.triangles.push_back({1, 1, 2});  // what a collapse leaves
  m.positions.push_back({5, 5, 5});
  m = tagged(m);
  compactMesh(m);
  EXPECT_EQ(m.triangles.size(), 4u);
  EXPECT_EQ(m.positions.size(), 4u);
  EXPECT_EQ(m.colors.size(), 4u);
}

TEST(VertexRemap, WeldingKeepsTheLowestVertexsValues) {
  // Two cubes sharing an edge, split apart along it, then welded back.
  const SurfaceMesh joined = test::cubesSharingAnEdge();
  SurfaceMesh m = tagged(joined);
  const std::uint32_t n = std::uint32_t(m.positions.size());
  appendVertexCopies(m, std::vector<std::uint32_t>{3, 6});
  ASSERT_EQ(m.positions.size(), n + 2);
  std::vector<std::uint32_t> new_index(n + 2);
  std::iota(new_index.begin(), new_index.end(), 0u);
  new_index[n] = 3, new_index[n + 1] = 6;
  m.triangles.push_back({n, n + 1, 0});  // uses the copies
  remapVertices(m, new_index);
  ASSERT_EQ(m.positions.size(), n);
  std::vector<std::uint32_t> identity(n);
  std::iota(identity.begin(), identity.end(), 0u);
  expectCarried(tagged(joined), m, identity);
  EXPECT_EQ(m.triangles.back(), (std::array<std::uint32_t, 3>{3, 6, 0}));
}

TEST(VertexRemap, SplittingCopiesEveryArray) {
  const SurfaceMesh in = tagged(test::tetrahedron());
  SurfaceMesh m = in;
  appendVertexCopies(m, std::vector<std::uint32_t>{3, 0, 3});
  expectCarried(in, m, {0, 1, 2, 3, 3, 0, 3});
  EXPECT_EQ(m.triangles, in.triangles);
}

// An array neither empty nor vertex-sized is a programming error, caught
// before anything changes, whichever operation meets it.
TEST(VertexRemap, AnArrayOfTheWrongSizeIsAnError) {
  SurfaceMesh m = tagged(test::tetrahedron());
  m.curvature.pop_back();
  const SurfaceMesh before = m;
  try {
    requireVertexArrays(m);
    FAIL() << "no error";
  } catch (const std::logic_error& e) {
    EXPECT_NE(std::string(e.what()).find("curvature holds 3 values for 4 vertices"), std::string::npos) << e.what();
  }
  EXPECT_THROW(gatherVertices(m, std::vector<std::uint32_t>{0}), std::logic_error);
  EXPECT_THROW(compactVertices(m), std::logic_error);
  EXPECT_THROW(compactMesh(m), std::logic_error);
  EXPECT_THROW(appendVertexCopies(m, std::vector<std::uint32_t>{1}), std::logic_error);
  EXPECT_EQ(m.positions, before.positions);
  EXPECT_EQ(m.colors, before.colors);
  EXPECT_EQ(m.curvature, before.curvature);
  EXPECT_EQ(m.triangles, before.triangles);
}

TEST(VertexRemap, BadIndicesAreErrorsAndChangeNothing) {
  SurfaceMesh m = tagged(test::tetrahedron());
  const SurfaceMesh before = m;
  EXPECT_THROW(gatherVertices(m, std::vector<std::uint32_t>{4}), std::out_of_range);
  EXPECT_THROW(appendVertexCopies(m, std::vector<std::uint32_t>{9}), std::out_of_range);
  EXPECT_THROW(remapVertices(m, std::vector<std::uint32_t>{0, 1, 2}), std::logic_error);     // not one per vertex
  EXPECT_THROW(remapVertices(m, std::vector<std::uint32_t>{0, 1, 2, 4}), std::logic_error);  // a gap at 3
  EXPECT_THROW(remapVertices(m, std::vector<std::uint32_t>{0, 1, 2, kDroppedVertex}), std::logic_error);  // in use
  EXPECT_EQ(m.positions, before.positions);
  EXPECT_EQ(m.triangles, before.triangles);
  EXPECT_EQ(m.durability, before.durability);
}

}  // namespace
}  // namespace rockbake
