// The mesh kernel's edge table (geometry/edge_table.h; docs/mesh-kernel.md) on
// analytic meshes whose counts are known: V − E + F = 2 for a closed genus-0
// surface.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <stdexcept>
#include <vector>

#include "geometry/disjoint_set.h"
#include "geometry/edge_table.h"
#include "geometry/mesh_checks.h"
#include "mesh_fixtures.h"

namespace rockbake {
namespace {

struct EdgeCounts {
  std::size_t edges = 0, paired = 0, boundary = 0, non_manifold = 0, misoriented = 0;
};

EdgeCounts count(const EdgeTable& table) {
  EdgeCounts n;
  for (const EdgeTable::Edge& e : table.edges()) {
    ++n.edges;
    n.paired += e.paired(), n.boundary += e.boundary(), n.non_manifold += e.nonManifold();
    n.misoriented += e.misoriented();
  }
  return n;
}

// The pieces of the faces joined across paired edges (not through shared vertices).
std::size_t piecesAcrossEdges(const EdgeTable& table, std::size_t faces) {
  DisjointSet pieces(faces);
  for (std::uint32_t c = 0; c < table.cornerCount(); ++c)
    if (table.twin(c) != EdgeTable::kNone) pieces.unite(table.face(c), table.face(table.twin(c)));
  const std::vector<std::uint32_t> labels = pieces.labels();
  return labels.empty() ? 0 : *std::max_element(labels.begin(), labels.end()) + 1;
}

TEST(EdgeTable, TetrahedronHasSixPairedEdgesAndEveryFaceTheOthersAsNeighbours) {
  const SurfaceMesh m = test::tetrahedron();
  const EdgeTable table(m.triangles);
  const EdgeCounts n = count(table);
  EXPECT_EQ(n.edges, 6u);
  EXPECT_EQ(n.paired, 6u);
  EXPECT_EQ(table.openEdgeCount(), 0u);
  EXPECT_EQ(m.positions.size() - n.edges + m.triangles.size(), 2u);
  for (std::uint32_t t = 0; t < 4; ++t) {
    std::set<std::uint32_t> across;
    for (std::uint32_t k = 0; k < 3; ++k) across.insert(table.faceAcross(3 * t + k));
    std::set<std::uint32_t> others{0, 1, 2, 3};
    others.erase(t);
    EXPECT_EQ(across, others) << t;
  }
}

TEST(EdgeTable, TwinsRunTheOtherWayAndPointBack) {
  const SurfaceMesh m = test::unitCube();
  const EdgeTable table(m.triangles);
  ASSERT_EQ(table.cornerCount(), 36u);
  const auto from = [&](std::uint32_t c) { return m.triangles[c / 3][c % 3]; };
  for (std::uint32_t c = 0; c < table.cornerCount(); ++c) {
    const std::uint32_t t = table.twin(c);
    ASSERT_NE(t, EdgeTable::kNone) << c;
    EXPECT_EQ(table.twin(t), c);
    EXPECT_EQ(from(t), from(table.next(c)));  // t runs from c's end to its start
    EXPECT_EQ(from(table.next(t)), from(c));
    EXPECT_NE(table.face(t), table.face(c));
    EXPECT_EQ(table.edgeOf(t), table.edgeOf(c));
    const EdgeTable::Edge& e = table.edge(table.edgeOf(c));
    EXPECT_EQ(std::min(from(c), from(table.next(c))), e.a);
    EXPECT_EQ(std::max(from(c), from(table.next(c))), e.b);
  }
  // Each edge lists its forward corner (a → b) then its backward one.
  for (std::uint32_t e = 0; e < table.edges().size(); ++e) {
    ASSERT_EQ(table.forwardCorners(e).size(), 1u);
    ASSERT_EQ(table.backwardCorners(e).size(), 1u);
    EXPECT_EQ(from(table.forwardCorners(e)[0]), table.edge(e).a);
    EXPECT_EQ(from(table.backwardCorners(e)[0]), table.edge(e).b);
  }
}

TEST(EdgeTable, CubeAsTrianglesOrQuadsIsClosed) {
  const SurfaceMesh triangles = test::unitCube(false), quads = test::unitCube(true);
  const EdgeCounts t = count(EdgeTable(triangles.triangles));
  EXPECT_EQ(t.edges, 18u);  // 12 cube edges and 6 diagonals
  EXPECT_EQ(t.paired, 18u);
  const EdgeTable quad_table(quads.triangles, quads.quads);
  const EdgeCounts q = count(quad_table);
  EXPECT_EQ(q.edges, 12u);
  EXPECT_EQ(q.paired, 12u);
  EXPECT_EQ(quads.positions.size() - q.edges + quads.quads.size(), 2u);
  // Quad corners: four to a face, next and prev going round it.
  ASSERT_EQ(quad_table.cornerCount(), 24u);
  for (std::uint32_t c = 0; c < 24; ++c) {
    EXPECT_EQ(quad_table.face(c), c / 4);
    EXPECT_EQ(quad_table.next(quad_table.prev(c)), c);
    EXPECT_EQ(quad_table.face(quad_table.next(c)), c / 4);
    EXPECT_EQ(quad_table.next(quad_table.next(quad_table.next(quad_table.next(c)))), c);
  }
  EXPECT_TRUE(findOpenEdges(quads).empty());
  EXPECT_NEAR(signedVolume(quads), 1.0, 1e-12);
  EXPECT_NEAR(signedVolume(triangles), 1.0, 1e-12);
}

TEST(EdgeTable, CubesSharingAnEdgeHaveOneNonManifoldEdgeOfFourFaces) {
  const SurfaceMesh m = test::cubesSharingAnEdge();
  ASSERT_EQ(m.positions.size(), 14u);  // two corners shared
  const EdgeTable table(m.triangles);
  const EdgeCounts n = count(table);
  EXPECT_EQ(n.edges, 35u);
  EXPECT_EQ(n.non_manifold, 1u);
  EXPECT_EQ(n.paired, 34u);
  EXPECT_EQ(table.openEdgeCount(), 1u);
  const std::vector<OpenEdge> open = findOpenEdges(m);
  ASSERT_EQ(open.size(), 1u);
  EXPECT_EQ(open[0].uses, 4);
  const std::uint32_t e = table.findEdge(open[0].b, open[0].a);
  ASSERT_NE(e, EdgeTable::kNone);
  EXPECT_EQ(table.forwardCorners(e).size(), 2u);
  EXPECT_EQ(table.backwardCorners(e).size(), 2u);
  for (std::uint32_t c : table.forwardCorners(e)) EXPECT_EQ(table.twin(c), EdgeTable::kNone);
  // Across paired edges the cubes are apart; through shared vertices, one piece.
  EXPECT_EQ(piecesAcrossEdges(table, m.triangles.size()), 2u);
}

TEST(EdgeTable, CubesSharingAVertexAreEdgeManifoldButTwoPiecesAcrossEdges) {
  const SurfaceMesh m = test::cubesSharingAVertex();
  ASSERT_EQ(m.positions.size(), 15u);
  const EdgeTable table(m.triangles);
  const EdgeCounts n = count(table);
  EXPECT_EQ(n.edges, 36u);
  EXPECT_EQ(n.paired, 36u);
  EXPECT_EQ(table.openEdgeCount(), 0u);
  EXPECT_EQ(piecesAcrossEdges(table, m.triangles.size()), 2u);
  DisjointSet through_vertices(m.positions.size());
  for (const auto& t : m.triangles) through_vertices.unite(t[0], t[1]), through_vertices.unite(t[0], t[2]);
  EXPECT_TRUE(through_vertices.connected(0, 14));
}

TEST(EdgeTable, AHoleIsARingOfBoundaryEdges) {
  const SurfaceMesh m = test::openBox();
  const EdgeTable table(m.triangles);
  const EdgeCounts n = count(table);
  EXPECT_EQ(n.edges, 17u);
  EXPECT_EQ(n.boundary, 4u);
  EXPECT_EQ(n.paired, 13u);
  std::set<std::uint32_t> rim;
  for (std::uint32_t i = 0; i < table.edges().size(); ++i) {
    const EdgeTable::Edge& e = table.edge(i);
    if (!e.boundary()) continue;
    EXPECT_EQ(m.positions[e.a][2], 1.0f);
    EXPECT_EQ(m.positions[e.b][2], 1.0f);
    rim.insert(e.a), rim.insert(e.b);
    const std::uint32_t c = e.forward ? table.forwardCorners(i)[0] : table.backwardCorners(i)[0];
    EXPECT_EQ(table.faceAcross(c), EdgeTable::kNone);
  }
  EXPECT_EQ(rim.size(), 4u);
  EXPECT_EQ(findOpenEdges(m).size(), 4u);
}

TEST(EdgeTable, AFlippedFaceMakesMisorientedEdges) {
  SurfaceMesh m = test::tetrahedron();
  std::swap(m.triangles[3][1], m.triangles[3][2]);
  const EdgeCounts n = count(EdgeTable(m.triangles));
  EXPECT_EQ(n.misoriented, 3u);
  EXPECT_EQ(n.paired, 3u);
}

TEST(EdgeTable, IndexBufferGivesTheSameTable) {
  const SurfaceMesh m = test::cubesSharingAnEdge();
  std::vector<std::uint32_t> indices;
  for (const auto& t : m.triangles) indices.insert(indices.end(), t.begin(), t.end());
  const EdgeTable a(m.triangles), b(indices);
  ASSERT_EQ(a.edges().size(), b.edges().size());
  for (std::uint32_t e = 0; e < a.edges().size(); ++e) {
    EXPECT_EQ(a.edge(e).a, b.edge(e).a);
    EXPECT_EQ(a.edge(e).b, b.edge(e).b);
    EXPECT_TRUE(std::ranges::equal(a.forwardCorners(e), b.forwardCorners(e)));
    EXPECT_TRUE(std::ranges::equal(a.backwardCorners(e), b.backwardCorners(e)));
  }
  EXPECT_TRUE(std::ranges::equal(a.twins(), b.twins()));
  indices.pop_back();
  EXPECT_THROW(EdgeTable{indices}, std::invalid_argument);
}

TEST(EdgeTable, FindsEdgesEitherWayRound) {
  const SurfaceMesh m = test::tetrahedron();
  const EdgeTable table(m.triangles);
  for (std::uint32_t a = 0; a < 4; ++a)
    for (std::uint32_t b = 0; b < 4; ++b) {
      const std::uint32_t e = table.findEdge(a, b);
      if (a == b) {
        EXPECT_EQ(e, EdgeTable::kNone);
        continue;
      }
      ASSERT_NE(e, EdgeTable::kNone);
      EXPECT_EQ(e, table.findEdge(b, a));
      EXPECT_EQ(table.edge(e).a, std::min(a, b));
    }
  EXPECT_EQ(table.findEdge(0, 7), EdgeTable::kNone);
}

// A triangle with a repeated vertex: its edge from the vertex to itself counts backward, open.
TEST(EdgeTable, ARepeatedVertexMakesAnOpenLoopEdge) {
  const std::vector<std::array<std::uint32_t, 3>> triangles{{0, 0, 1}};
  const EdgeTable table(triangles);
  ASSERT_EQ(table.edges().size(), 2u);
  EXPECT_EQ(table.edge(0).a, 0u);
  EXPECT_EQ(table.edge(0).b, 0u);
  EXPECT_EQ(table.edge(0).forward, 0u);
  EXPECT_EQ(table.edge(0).backward, 1u);
  EXPECT_TRUE(table.edge(1).paired());  // 0 → 1 and 1 → 0, both in the one triangle
  EXPECT_EQ(table.faceAcross(1), 0u);
}

}  // namespace
}  // namespace rockbake
