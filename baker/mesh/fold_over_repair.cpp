#include "mesh/fold_over_repair.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <iterator>
#include <unordered_map>
#include <utility>
#include <vector>

#include "core/vec3.h"
#include "geometry/edge_table.h"
#include "geometry/triangle_geometry.h"
#include "geometry/vertex_faces.h"
#include "geometry/vertex_remap.h"
#include "mesh/mesh_defects.h"
#include "mesh/subdivide.h"

namespace rockbake {
namespace {

constexpr std::uint32_t kNone = EdgeTable::kNone;

std::uint64_t edgeKey(std::uint32_t a, std::uint32_t b) {
  return std::uint64_t(std::min(a, b)) << 32 | std::max(a, b);
}

// The adjacency the flips keep: the edge table's twins (corner 3t + k is the
// half-edge from triangles[t][k] to the next corner), followed through every
// flip, and the edges the flips made or took away.
class Flips {
 public:
  explicit Flips(SurfaceMesh& mesh)
      : m_(mesh), table_(mesh.triangles), twin_(table_.twins().begin(), table_.twins().end()) {}

  bool defective(std::uint32_t t) const { return isDefective(m_, twin_, t); }
  // Flips the edge of t from corner k; true if done.
  bool tryFlip(std::uint32_t t, std::uint32_t k);

 private:
  std::uint32_t faceAcross(std::uint32_t c) const { return twin_[c] == kNone ? kNone : twin_[c] / 3; }
  bool hasEdge(std::uint32_t a, std::uint32_t b) const {
    const auto it = changed_.find(edgeKey(a, b));
    return it != changed_.end() ? it->second : table_.findEdge(a, b) != EdgeTable::kNone;
  }
  Vec3d normal(const std::array<std::uint32_t, 3>& t) const {
    return triangleNormal(m_.positions[t[0]], m_.positions[t[1]], m_.positions[t[2]]);
  }
  bool zeroArea(const std::array<std::uint32_t, 3>& t) const {
    return isZeroArea(m_.positions[t[0]], m_.positions[t[1]], m_.positions[t[2]]);
  }
  // The unit normals of the triangles around the quad t ∪ u, summed.
  Vec3d surroundings(std::uint32_t t, std::uint32_t u) const;
  void link(std::uint32_t c, std::uint32_t d) {
    twin_[c] = d;
    if (d != kNone) twin_[d] = c;
  }

  SurfaceMesh& m_;
  const EdgeTable table_;
  std::vector<std::uint32_t> twin_;
  std::unordered_map<std::uint64_t, bool> changed_;  // edge key → whether it exists now
};

Vec3d Flips::surroundings(std::uint32_t t, std::uint32_t u) const {
  Vec3d reference{0, 0, 0};
  for (std::uint32_t f : {t, u})
    for (std::uint32_t j = 0; j < 3; ++j) {
      const std::uint32_t g = faceAcross(3 * f + j);
      if (g == t || g == u || g == kNone) continue;
      const Vec3d n = normal(m_.triangles[g]);
      const double len = length(n);
      if (len > 0) reference = add(reference, divide(n, len));
    }
  return reference;
}

bool Flips::tryFlip(std::uint32_t t, std::uint32_t k) {
  const auto tri = m_.triangles[t];
  const std::uint32_t a = tri[k], b = tri[(k + 1) % 3], c = tri[(k + 2) % 3];
  const std::uint32_t ab = 3 * t + k, ba = twin_[ab];
  if (ba == kNone) return false;
  const std::uint32_t u = ba / 3;
  const auto& nb = m_.triangles[u];
  std::uint32_t d = kNone;
  for (std::uint32_t j = 0; j < 3; ++j)
    if (nb[j] != a && nb[j] != b) d = nb[j];
  if (d == kNone || d == c || hasEdge(c, d)) return false;
  const Vec3d reference = surroundings(t, u);
  const std::array<std::uint32_t, 3> t1{a, d, c}, t2{b, c, d};
  if (zeroArea(t1) || zeroArea(t2)) return false;
  if (dot(normal(t1), reference) <= 0 || dot(normal(t2), reference) <= 0) return false;
  // Apply: edge ab becomes cd; t takes (a, d, c), u takes (b, c, d). u ran
  // b → a → d, so its corners after ba are a → d and d → b.
  const std::uint32_t ad = 3 * u + (ba % 3 + 1) % 3, db = 3 * u + (ba % 3 + 2) % 3;
  const std::uint32_t out_bc = twin_[3 * t + (k + 1) % 3], out_ca = twin_[3 * t + (k + 2) % 3];
  const std::uint32_t out_ad = twin_[ad], out_db = twin_[db];
  m_.triangles[t] = t1, m_.triangles[u] = t2;
  link(3 * t, out_ad), link(3 * t + 1, 3 * u + 1), link(3 * t + 2, out_ca);
  link(3 * u, out_bc), link(3 * u + 2, out_db);
  changed_[edgeKey(a, b)] = false;
  changed_[edgeKey(c, d)] = true;
  return true;
}

double edgeLength2(const SurfaceMesh& m, const std::array<std::uint32_t, 3>& tri, std::uint32_t k) {
  return distanceSquared(toVec3d(m.positions[tri[(k + 1) % 3]]), toVec3d(m.positions[tri[k]]));
}

// Up to eight passes over the triangles in index order, each defective one's
// edges tried longest first (a zero-area cap is fixed by flipping its long edge).
void flipDefects(SurfaceMesh& mesh, Flips& flips) {
  for (int pass = 0; pass < 8; ++pass) {
    bool changed = false;
    for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t) {
      if (!flips.defective(t)) continue;
      std::array<std::uint32_t, 3> order{0, 1, 2};
      const auto len2 = [&](std::uint32_t k) { return edgeLength2(mesh, mesh.triangles[t], k); };
      std::sort(order.begin(), order.end(), [&](std::uint32_t x, std::uint32_t y) { return len2(x) > len2(y); });
      for (std::uint32_t k : order)
        if (flips.tryFlip(t, k)) {
          changed = true;
          break;
        }
    }
    if (!changed) break;
  }
}

// The vertices sharing a triangle with x, sorted, once each.
std::vector<std::uint32_t> ring(const SurfaceMesh& m, const VertexFaces& around, std::uint32_t x) {
  std::vector<std::uint32_t> out;
  for (std::uint32_t f : around[x])
    for (std::uint32_t y : m.triangles[f])
      if (y != x) out.push_back(y);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

// Half-edge collapse v → w, when the link condition holds and every triangle
// that moves keeps its area and its side. The two triangles on the edge are
// left with a repeated index (compactMesh drops them); the vertices of every
// changed triangle are touched, and a touched vertex is not collapsed again
// this round (`around` is then stale there). True if done.
bool tryCollapse(SurfaceMesh& m, const VertexFaces& around, std::vector<char>& touched, std::uint32_t v,
                 std::uint32_t w) {
  if (touched[v] || touched[w]) return false;
  const std::vector<std::uint32_t> nv = ring(m, around, v), nw = ring(m, around, w);
  std::vector<std::uint32_t> common;
  std::set_intersection(nv.begin(), nv.end(), nw.begin(), nw.end(), std::back_inserter(common));
  std::size_t shared = 0;  // triangles with both v and w
  for (std::uint32_t f : around[v])
    for (std::uint32_t y : m.triangles[f]) shared += y == w;
  if (shared != 2 || common.size() != 2) return false;
  for (std::uint32_t f : around[v]) {
    auto tri = m.triangles[f];
    if (std::find(tri.begin(), tri.end(), w) != tri.end()) continue;  // goes away
    const Vec3d before = triangleNormal(m.positions[tri[0]], m.positions[tri[1]], m.positions[tri[2]]);
    for (auto& y : tri) y = y == v ? w : y;
    const auto &a = m.positions[tri[0]], &b = m.positions[tri[1]], &c = m.positions[tri[2]];
    if (isZeroArea(a, b, c) || dot(before, triangleNormal(a, b, c)) <= 0) return false;
  }
  for (std::uint32_t f : around[v]) {
    auto& tri = m.triangles[f];
    for (std::uint32_t y : tri) touched[y] = 1;
    for (auto& y : tri) y = y == v ? w : y;  // the two on the edge become (w, w, x)
  }
  return true;
}

// What flips cannot fix: collapse one of each bad triangle's edges (shortest
// first) onto an existing vertex. True if any was collapsed.
bool collapseDefects(SurfaceMesh& mesh, const std::vector<std::uint32_t>& bad) {
  const VertexFaces around(mesh.triangles, mesh.positions.size());
  std::vector<char> touched(mesh.positions.size(), 0);
  bool collapsed = false;
  for (std::uint32_t t : bad) {
    const auto tri = mesh.triangles[t];
    std::array<std::pair<double, std::uint32_t>, 3> edges;
    for (std::uint32_t k = 0; k < 3; ++k) edges[k] = {edgeLength2(mesh, tri, k), k};
    std::sort(edges.begin(), edges.end());
    for (const auto& [len, k] : edges) {
      const std::uint32_t a = tri[k], b = tri[(k + 1) % 3];
      if (tryCollapse(mesh, around, touched, a, b) || tryCollapse(mesh, around, touched, b, a)) {
        collapsed = true;
        break;
      }
    }
  }
  return collapsed;
}

}  // namespace

std::size_t repairFoldOvers(SurfaceMesh& mesh) {
  requireVertexArrays(mesh);  // before a flip changes anything, not at the first compaction
  std::size_t left = 0;
  for (int round = 0; round < 6; ++round) {
    Flips flips(mesh);
    flipDefects(mesh, flips);
    std::vector<std::uint32_t> bad;
    for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t)
      if (flips.defective(t)) bad.push_back(t);
    left = bad.size();
    if (bad.empty() || !collapseDefects(mesh, bad)) break;
    compactMesh(mesh);
  }
  computeVertexNormals(mesh);
  return left;
}

}  // namespace rockbake
