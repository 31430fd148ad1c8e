// The mesh kernel's triangles around each vertex (geometry/vertex_faces.h; docs/mesh-kernel.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>
#include <vector>

#include "geometry/vertex_faces.h"
#include "mesh_fixtures.h"

namespace rockbake {
namespace {

TEST(VertexFaces, ListsEachVertexsTrianglesInOrder) {
  const SurfaceMesh m = test::tetrahedron();
  const VertexFaces around(m.triangles, m.positions.size());
  ASSERT_EQ(around.vertexCount(), 4u);
  for (std::uint32_t v = 0; v < 4; ++v) {
    std::vector<std::uint32_t> expected;
    for (std::uint32_t t = 0; t < 4; ++t)
      if (std::find(m.triangles[t].begin(), m.triangles[t].end(), v) != m.triangles[t].end()) expected.push_back(t);
    EXPECT_TRUE(std::ranges::equal(around[v], expected)) << v;
    EXPECT_EQ(around[v].size(), 3u);
  }
  const std::vector<std::array<std::uint32_t, 3>> pinched{{0, 0, 1}};
  EXPECT_EQ(VertexFaces(pinched, 2)[0].size(), 2u);  // listed once per corner
  EXPECT_THROW(VertexFaces(m.triangles, 3), std::out_of_range);
}

}  // namespace
}  // namespace rockbake
