#include "mesh/relax_fold_overs.h"

#include <algorithm>
#include <cstdint>
#include <vector>

#include "core/vec3.h"
#include "geometry/edge_table.h"
#include "geometry/vertex_faces.h"
#include "mesh/mesh_defects.h"
#include "mesh/subdivide.h"

namespace rockbake {
namespace {

void sortUnique(std::vector<std::uint32_t>& v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
}

struct Relaxation {
  SurfaceMesh& mesh;
  const EdgeTable edges{mesh.triangles};
  const VertexFaces around{mesh.triangles, mesh.positions.size()};

  std::size_t defects(const std::vector<std::uint32_t>& triangles) const {
    std::size_t n = 0;
    for (std::uint32_t t : triangles) n += isDefective(mesh, edges.twins(), t);
    return n;
  }

  // The triangles whose standing a move of v can change: v's own, whose
  // normals move, and their edge neighbours, which are judged against them.
  std::vector<std::uint32_t> region(std::uint32_t v) const {
    std::vector<std::uint32_t> r;
    for (std::uint32_t t : around[v]) {
      r.push_back(t);
      for (std::uint32_t k = 0; k < 3; ++k)
        if (const std::uint32_t u = edges.faceAcross(3 * t + k); u != EdgeTable::kNone) r.push_back(u);
    }
    sortUnique(r);
    return r;
  }

  // The vertices of every defective triangle, sorted, once each.
  std::vector<std::uint32_t> defectiveVertices() const {
    std::vector<std::uint32_t> vertices;
    for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t)
      if (isDefective(mesh, edges.twins(), t))
        vertices.insert(vertices.end(), mesh.triangles[t].begin(), mesh.triangles[t].end());
    sortUnique(vertices);
    return vertices;
  }

  // Towards the neighbours' mean first, then towards each neighbour in turn;
  // the first move that leaves fewer defects around v is kept. True if one was.
  bool relax(std::uint32_t v) {
    const std::vector<std::uint32_t> r = region(v);
    const std::size_t before = defects(r);
    if (before == 0) return false;
    std::vector<std::uint32_t> ring;
    for (std::uint32_t t : around[v])
      for (std::uint32_t w : mesh.triangles[t])
        if (w != v) ring.push_back(w);
    sortUnique(ring);
    Vec3d mean{0, 0, 0};
    for (std::uint32_t w : ring) mean = add(mean, divide(toVec3d(mesh.positions[w]), double(ring.size())));
    std::vector<Vec3d> goals{mean};
    for (std::uint32_t w : ring) goals.push_back(toVec3d(mesh.positions[w]));
    const Vec3f original = mesh.positions[v];
    const Vec3d from = toVec3d(original);
    bool moved = false;
    for (const Vec3d& goal : goals) {
      for (double step : {1.0, 0.5, 0.25}) {
        if (&goal != &goals[0] && step == 1.0) continue;  // onto a neighbour: zero area
        mesh.positions[v] = toVec3f(add(from, scale(sub(goal, from), step)));
        if (defects(r) < before) {
          moved = true;
          break;
        }
        mesh.positions[v] = original;
      }
      if (mesh.positions[v] != original) break;
    }
    return moved;
  }
};

}  // namespace

std::size_t relaxFoldOvers(SurfaceMesh& mesh) {
  Relaxation relaxation{mesh};
  for (int round = 0; round < 10; ++round) {
    bool moved = false;
    for (std::uint32_t v : relaxation.defectiveVertices()) moved |= relaxation.relax(v);
    if (!moved) break;
  }
  computeVertexNormals(mesh);
  std::size_t left = 0;
  for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t) left += isDefective(mesh, relaxation.edges.twins(), t);
  return left;
}

}  // namespace rockbake
