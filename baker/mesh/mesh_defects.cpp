#include "mesh/mesh_defects.h"

#include <algorithm>

#include "geometry/disjoint_set.h"
#include "geometry/mesh_checks.h"
#include "geometry/triangle_geometry.h"

namespace rockbake {
namespace {

void sortUnique(std::vector<std::uint32_t>& v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
}

// The pieces through shared vertices, and those enclosing positive volume.
void countPieces(const SurfaceMesh& m, MeshDefects& d) {
  const std::vector<std::uint32_t> piece = pieceOfVertex(m);
  const std::uint32_t pieces = piece.empty() ? 0 : *std::max_element(piece.begin(), piece.end()) + 1;
  std::vector<char> has_triangles(pieces, 0);
  std::vector<double> volume(pieces, 0.0);
  for (const auto& t : m.triangles) {
    has_triangles[piece[t[0]]] = 1;
    volume[piece[t[0]]] += tetVolume(m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]);
  }
  for (std::uint32_t p = 0; p < pieces; ++p) d.components += has_triangles[p], d.shells += volume[p] > 0;
}

}  // namespace

bool isDefective(const SurfaceMesh& m, std::span<const std::uint32_t> twins, std::uint32_t t) {
  const auto normalOf = [&](std::uint32_t f) {
    const auto& tri = m.triangles[f];
    return triangleNormal(m.positions[tri[0]], m.positions[tri[1]], m.positions[tri[2]]);
  };
  const auto& tri = m.triangles[t];
  return isZeroArea(m.positions[tri[0]], m.positions[tri[1]], m.positions[tri[2]]) || foldsOver(twins, t, normalOf);
}

std::vector<std::uint32_t> pieceOfVertex(const SurfaceMesh& m) {
  DisjointSet pieces(m.positions.size());
  for (const auto& t : m.triangles) pieces.unite(t[0], t[1]), pieces.unite(t[0], t[2]);
  return pieces.labels();
}

MeshDefects checkMesh(const SurfaceMesh& m) {
  MeshDefects d;
  const std::size_t nt = m.triangles.size();
  if (nt == 0) return d;
  std::vector<Vec3d> normal(nt);
  for (std::size_t t = 0; t < nt; ++t) {
    const auto& tri = m.triangles[t];
    const auto &a = m.positions[tri[0]], &b = m.positions[tri[1]], &c = m.positions[tri[2]];
    normal[t] = triangleNormal(a, b, c);
    if (isZeroArea(a, b, c)) {
      ++d.zero_area;
      d.defect_vertices.insert(d.defect_vertices.end(), tri.begin(), tri.end());
    }
  }
  const EdgeTable edges(m.triangles);
  for (const EdgeTable::Edge& e : edges.edges())
    if (!e.paired()) {
      ++d.open_edges;
      d.open_edge_vertices.push_back(e.a);
      d.open_edge_vertices.push_back(e.b);
    }
  for (std::uint32_t t = 0; t < nt; ++t)
    if (foldsOver(edges.twins(), t, [&](std::uint32_t f) { return normal[f]; })) {
      ++d.fold_overs;
      d.defect_vertices.insert(d.defect_vertices.end(), m.triangles[t].begin(), m.triangles[t].end());
    }
  sortUnique(d.open_edge_vertices);
  d.defect_vertices.insert(d.defect_vertices.end(), d.open_edge_vertices.begin(), d.open_edge_vertices.end());
  sortUnique(d.defect_vertices);
  countPieces(m, d);
  d.volume = signedVolume(m);
  return d;
}

}  // namespace rockbake
