#include "mesh/collapsed_specks.h"

#include <algorithm>
#include <cstdint>
#include <vector>

#include "geometry/edge_table.h"
#include "geometry/vertex_remap.h"
#include "mesh/mesh_defects.h"
#include "mesh/subdivide.h"

namespace rockbake {

std::size_t dropCollapsedSpecks(SurfaceMesh& mesh, std::size_t max_triangles) {
  requireVertexArrays(mesh);  // before a triangle is dropped, not at the compaction
  const std::vector<std::uint32_t> piece = pieceOfVertex(mesh);
  const EdgeTable edges(mesh.triangles);
  std::vector<std::size_t> size(mesh.positions.size(), 0);
  std::vector<char> defective(mesh.positions.size(), 0);
  for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t) {
    const std::uint32_t p = piece[mesh.triangles[t][0]];
    ++size[p];
    if (isDefective(mesh, edges.twins(), t)) defective[p] = 1;
  }
  const std::size_t before = mesh.triangles.size();
  std::erase_if(mesh.triangles, [&](const auto& t) {
    const std::uint32_t p = piece[t[0]];
    return defective[p] && size[p] <= max_triangles;
  });
  const std::size_t dropped = before - mesh.triangles.size();
  if (dropped > 0) {
    compactMesh(mesh);
    computeVertexNormals(mesh);
  }
  return dropped;
}

}  // namespace rockbake
