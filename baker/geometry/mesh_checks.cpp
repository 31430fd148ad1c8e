#include "geometry/mesh_checks.h"

#include <algorithm>
#include <limits>

#include "geometry/edge_table.h"
#include "geometry/triangle_geometry.h"

namespace rockbake {
namespace {

std::vector<OpenEdge> openEdges(const EdgeTable& table) {
  std::vector<OpenEdge> open;
  open.reserve(table.openEdgeCount());
  for (const EdgeTable::Edge& e : table.edges())
    if (!e.paired()) open.push_back({e.a, e.b, int(e.faces())});
  return open;
}

}  // namespace

std::vector<OpenEdge> findOpenEdges(const TriangleMesh& mesh) {
  return openEdges(EdgeTable(mesh.triangles));
}

std::vector<OpenEdge> findOpenEdges(const SurfaceMesh& mesh) {
  return openEdges(EdgeTable(mesh.triangles, mesh.quads));
}

double signedVolume(const TriangleMesh& m) {
  double v = 0.0;
  for (const auto& t : m.triangles) v += tetVolume(m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]);
  return v;
}

double signedVolume(const SurfaceMesh& m) {
  double v = 0.0;
  const auto& p = m.positions;
  for (const auto& t : m.triangles) v += tetVolume(p[t[0]], p[t[1]], p[t[2]]);
  for (const auto& q : m.quads) v += tetVolume(p[q[0]], p[q[1]], p[q[2]]) + tetVolume(p[q[0]], p[q[2]], p[q[3]]);
  return v;
}

void updateBounds(AssetMeshes& meshes) {
  constexpr float kMax = std::numeric_limits<float>::max();
  std::array<float, 3> lo{kMax, kMax, kMax}, hi{-kMax, -kMax, -kMax};
  for (const SurfaceMesh* m : {&meshes.rock, &meshes.colluvium})
    for (const auto& p : m->positions)
      for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], p[a]), hi[a] = std::max(hi[a], p[a]);
  if (meshes.rock.positions.empty() && meshes.colluvium.positions.empty()) lo = hi = {};
  meshes.bounds_min = lo;
  meshes.bounds_max = hi;
}

}  // namespace rockbake
