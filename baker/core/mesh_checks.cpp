#include "core/mesh_checks.h"

#include <algorithm>
#include <limits>

#include "core/triangle_geometry.h"

namespace rockbake {
namespace {

// (min, max, direction) of every edge of the faces.
template <class Face>
void countEdges(const std::vector<Face>& faces, std::vector<std::array<std::uint32_t, 3>>& edges) {
  for (const auto& f : faces)
    for (std::size_t i = 0; i < f.size(); ++i) {
      const std::uint32_t a = f[i], b = f[(i + 1) % f.size()];
      edges.push_back({std::min(a, b), std::max(a, b), a < b ? 0u : 1u});
    }
}

// Sorted (a, b, direction) triples → the edges not used once in each direction.
std::vector<OpenEdge> openEdges(std::vector<std::array<std::uint32_t, 3>> edges) {
  std::sort(edges.begin(), edges.end());
  std::vector<OpenEdge> open;
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    int uses[2] = {0, 0};
    for (; j < edges.size() && edges[j][0] == edges[i][0] && edges[j][1] == edges[i][1]; ++j) ++uses[edges[j][2]];
    if (uses[0] != 1 || uses[1] != 1) open.push_back({edges[i][0], edges[i][1], uses[0] + uses[1]});
    i = j;
  }
  return open;
}

}  // namespace

std::vector<OpenEdge> findOpenEdges(const TriangleMesh& mesh) {
  std::vector<std::array<std::uint32_t, 3>> edges;
  countEdges(mesh.triangles, edges);
  return openEdges(std::move(edges));
}

std::vector<OpenEdge> findOpenEdges(const SurfaceMesh& mesh) {
  std::vector<std::array<std::uint32_t, 3>> edges;
  countEdges(mesh.triangles, edges);
  countEdges(mesh.quads, edges);
  return openEdges(std::move(edges));
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
