#include "mesh/mesh_defects.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <numeric>
#include <unordered_map>
#include <utility>
#include <vector>

#include "core/disjoint_set.h"
#include "core/mesh_checks.h"
#include "core/triangle_geometry.h"
#include "core/vec3.h"
#include "core/vertex_remap.h"
#include "mesh/subdivide.h"

namespace rockbake {
namespace {

// The piece (triangles connected through shared vertices) of every vertex,
// numbered by the pieces' lowest vertices.
std::vector<std::uint32_t> pieceOfVertex(const SurfaceMesh& m) {
  DisjointSet pieces(m.positions.size());
  for (const auto& t : m.triangles) pieces.unite(t[0], t[1]), pieces.unite(t[0], t[2]);
  return pieces.labels();
}

}  // namespace

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
  // Directed edges sorted by undirected key: the faces on each edge side by side.
  std::vector<std::pair<std::uint64_t, std::uint32_t>> edges;  // (key, triangle << 2 | forward)
  edges.reserve(3 * nt);
  for (std::size_t t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) {
      const std::uint64_t a = m.triangles[t][k], b = m.triangles[t][(k + 1) % 3];
      edges.push_back({std::min(a, b) << 32 | std::max(a, b), std::uint32_t(t << 2 | (a < b ? 1u : 0u))});
    }
  std::sort(edges.begin(), edges.end());
  std::vector<std::array<std::uint32_t, 3>> neighbours(nt, {UINT32_MAX, UINT32_MAX, UINT32_MAX});
  std::vector<int> filled(nt, 0);
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    int forward = 0, backward = 0;
    for (; j < edges.size() && edges[j].first == edges[i].first; ++j) (edges[j].second & 1 ? forward : backward)++;
    if (forward != 1 || backward != 1) {
      ++d.open_edges;
      d.open_edge_vertices.push_back(std::uint32_t(edges[i].first >> 32));
      d.open_edge_vertices.push_back(std::uint32_t(edges[i].first & 0xffffffffu));
    } else {
      const std::uint32_t a = edges[i].second >> 2, b = edges[i + 1].second >> 2;
      neighbours[a][filled[a]++ % 3] = b, neighbours[b][filled[b]++ % 3] = a;
    }
    i = j;
  }
  for (std::size_t t = 0; t < nt; ++t) {
    if (filled[t] != 3) continue;
    bool against_all = true;
    for (std::uint32_t u : neighbours[t]) against_all &= dot(normal[t], normal[u]) < 0;
    d.fold_overs += against_all;
    if (against_all) d.defect_vertices.insert(d.defect_vertices.end(), m.triangles[t].begin(), m.triangles[t].end());
  }
  const auto sortUnique = [](std::vector<std::uint32_t>& v) {
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
  };
  sortUnique(d.open_edge_vertices);
  d.defect_vertices.insert(d.defect_vertices.end(), d.open_edge_vertices.begin(), d.open_edge_vertices.end());
  sortUnique(d.defect_vertices);
  // Components through shared vertices, and those enclosing positive volume.
  const std::vector<std::uint32_t> piece = pieceOfVertex(m);
  const std::uint32_t pieces = piece.empty() ? 0 : *std::max_element(piece.begin(), piece.end()) + 1;
  std::vector<char> has_triangles(pieces, 0);
  std::vector<double> volume(pieces, 0.0);
  for (const auto& t : m.triangles) {
    has_triangles[piece[t[0]]] = 1;
    volume[piece[t[0]]] += tetVolume(m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]);
  }
  for (std::uint32_t p = 0; p < pieces; ++p) d.components += has_triangles[p], d.shells += volume[p] > 0;
  d.volume = signedVolume(m);
  return d;
}

}  // namespace rockbake

namespace rockbake {
namespace {

std::uint64_t edgeKey(std::uint32_t a, std::uint32_t b) {
  return std::uint64_t(std::min(a, b)) << 32 | std::max(a, b);
}

struct FlipMesh {
  SurfaceMesh& m;
  std::unordered_map<std::uint64_t, std::array<std::uint32_t, 2>> faces_of_edge;

  explicit FlipMesh(SurfaceMesh& mesh) : m(mesh) {
    faces_of_edge.reserve(m.triangles.size() * 2);
    for (std::uint32_t t = 0; t < m.triangles.size(); ++t)
      for (int k = 0; k < 3; ++k) addFace(edgeKey(m.triangles[t][k], m.triangles[t][(k + 1) % 3]), t);
  }
  void addFace(std::uint64_t key, std::uint32_t t) {
    auto [it, fresh] = faces_of_edge.try_emplace(key, std::array<std::uint32_t, 2>{t, UINT32_MAX});
    if (!fresh) it->second[1] = t;
  }
  void replace(std::uint64_t key, std::uint32_t from, std::uint32_t to) {
    auto& f = faces_of_edge.at(key);
    (f[0] == from ? f[0] : f[1]) = to;
  }
  std::uint32_t across(std::uint32_t t, std::uint32_t a, std::uint32_t b) const {
    const auto it = faces_of_edge.find(edgeKey(a, b));
    if (it == faces_of_edge.end()) return UINT32_MAX;
    return it->second[0] == t ? it->second[1] : it->second[0];
  }
  Vec3d normal(const std::array<std::uint32_t, 3>& t) const {
    return triangleNormal(m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]);
  }
  bool zeroArea(const std::array<std::uint32_t, 3>& t) const {
    return isZeroArea(m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]);
  }
  bool defective(std::uint32_t t) const {
    const auto& tri = m.triangles[t];
    if (zeroArea(tri)) return true;
    const Vec3d n = normal(tri);
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t u = across(t, tri[k], tri[(k + 1) % 3]);
      if (u == UINT32_MAX || dot(n, normal(m.triangles[u])) >= 0) return false;
    }
    return true;
  }
  // Flips the edge of t from corner k; true if done.
  bool tryFlip(std::uint32_t t, int k) {
    const auto tri = m.triangles[t];
    const std::uint32_t a = tri[k], b = tri[(k + 1) % 3], c = tri[(k + 2) % 3];
    const std::uint32_t u = across(t, a, b);
    if (u == UINT32_MAX) return false;
    const auto& nb = m.triangles[u];
    std::uint32_t d = UINT32_MAX;
    for (int j = 0; j < 3; ++j)
      if (nb[j] != a && nb[j] != b) d = nb[j];
    if (d == UINT32_MAX || d == c || faces_of_edge.count(edgeKey(c, d))) return false;
    // The surroundings: the four outer neighbours' normals, each unit length.
    Vec3d reference{0, 0, 0};
    const std::array<std::array<std::uint32_t, 3>, 2> quad{tri, nb};
    for (std::uint32_t f : {t, u})
      for (int j = 0; j < 3; ++j) {
        const auto& ft = m.triangles[f];
        const std::uint32_t g = across(f, ft[j], ft[(j + 1) % 3]);
        if (g == t || g == u || g == UINT32_MAX) continue;
        const Vec3d n = normal(m.triangles[g]);
        const double len = length(n);
        if (len > 0) reference = add(reference, divide(n, len));
      }
    (void)quad;
    const std::array<std::uint32_t, 3> t1{a, d, c}, t2{b, c, d};
    if (zeroArea(t1) || zeroArea(t2)) return false;
    if (dot(normal(t1), reference) <= 0 || dot(normal(t2), reference) <= 0) return false;
    // Apply: edge ab becomes cd; t takes (a, d, c), u takes (b, c, d).
    faces_of_edge.erase(edgeKey(a, b));
    replace(edgeKey(b, c), t, u);  // bc moves from t to u
    replace(edgeKey(a, d), u, t);  // ad moves from u to t
    faces_of_edge[edgeKey(c, d)] = {t, u};
    m.triangles[t] = t1, m.triangles[u] = t2;
    return true;
  }
};

// Half-edge collapse v → w across triangle t's edge, when the link condition
// holds and every triangle that moves keeps its area and its side. Marks the
// two triangles on the edge dead (degenerate: index repeated); true if done.
bool tryCollapse(SurfaceMesh& m, const std::vector<std::vector<std::uint32_t>>& around, std::vector<char>& touched,
                 std::uint32_t v, std::uint32_t w) {
  if (touched[v] || touched[w]) return false;
  std::vector<std::uint32_t> nv, nw;
  const auto ring = [&](std::uint32_t x, std::vector<std::uint32_t>& out) {
    for (std::uint32_t f : around[x])
      for (std::uint32_t y : m.triangles[f])
        if (y != x) out.push_back(y);
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
  };
  ring(v, nv), ring(w, nw);
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
    if (isZeroArea(a, b, c)) return false;
    if (dot(before, triangleNormal(a, b, c)) <= 0) return false;
  }
  for (std::uint32_t f : around[v]) {
    auto& tri = m.triangles[f];
    for (std::uint32_t y : tri) touched[y] = 1;
    for (auto& y : tri) y = y == v ? w : y;  // the two on the edge become (w, w, x): dropped later
  }
  return true;
}

}  // namespace

std::size_t repairFoldOvers(SurfaceMesh& mesh) {
  std::size_t left = 0;
  for (int round = 0; round < 6; ++round) {
    FlipMesh fm(mesh);
    for (int pass = 0; pass < 8; ++pass) {
      bool changed = false;
      for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t) {
        if (!fm.defective(t)) continue;
        // Longest edge first: a zero-area cap is fixed by flipping its long edge.
        std::array<int, 3> order{0, 1, 2};
        const auto len2 = [&](int k) {
          const auto& tri = mesh.triangles[t];
          return distanceSquared(toVec3d(mesh.positions[tri[(k + 1) % 3]]), toVec3d(mesh.positions[tri[k]]));
        };
        std::sort(order.begin(), order.end(), [&](int x, int y) { return len2(x) > len2(y); });
        for (int k : order)
          if (fm.tryFlip(t, k)) {
            changed = true;
            break;
          }
      }
      if (!changed) break;
    }
    std::vector<std::uint32_t> bad;
    for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t)
      if (fm.defective(t)) bad.push_back(t);
    left = bad.size();
    if (bad.empty()) break;
    // What flips cannot fix: collapse one of the triangle's edges (shortest
    // first) onto an existing vertex, and flip again around the result.
    std::vector<std::vector<std::uint32_t>> around(mesh.positions.size());
    for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t)
      for (std::uint32_t v : mesh.triangles[t]) around[v].push_back(t);
    std::vector<char> touched(mesh.positions.size(), 0);
    bool collapsed = false;
    for (std::uint32_t t : bad) {
      const auto tri = mesh.triangles[t];
      std::array<std::pair<double, int>, 3> edges;
      for (int k = 0; k < 3; ++k) {
        edges[k] = {distanceSquared(toVec3d(mesh.positions[tri[(k + 1) % 3]]), toVec3d(mesh.positions[tri[k]])), k};
      }
      std::sort(edges.begin(), edges.end());
      bool done = false;
      for (const auto& [len, k] : edges) {
        const std::uint32_t a = tri[k], b = tri[(k + 1) % 3];
        if ((done = tryCollapse(mesh, around, touched, a, b) || tryCollapse(mesh, around, touched, b, a))) break;
      }
      collapsed |= done;
    }
    if (!collapsed) break;
    compactMesh(mesh);
  }
  computeVertexNormals(mesh);
  return left;
}

std::size_t relaxFoldOvers(SurfaceMesh& mesh) {
  FlipMesh fm(mesh);
  std::vector<std::vector<std::uint32_t>> around(mesh.positions.size());
  for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t)
    for (std::uint32_t v : mesh.triangles[t]) around[v].push_back(t);
  // The triangles whose standing a move of v can change: v's own, whose
  // normals move, and their edge neighbours, which are judged against them.
  const auto region = [&](std::uint32_t v) {
    std::vector<std::uint32_t> r;
    for (std::uint32_t t : around[v]) {
      r.push_back(t);
      const auto& tri = mesh.triangles[t];
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t u = fm.across(t, tri[k], tri[(k + 1) % 3]);
        if (u != UINT32_MAX) r.push_back(u);
      }
    }
    std::sort(r.begin(), r.end());
    r.erase(std::unique(r.begin(), r.end()), r.end());
    return r;
  };
  const auto defects = [&](const std::vector<std::uint32_t>& triangles) {
    std::size_t n = 0;
    for (std::uint32_t t : triangles) n += fm.defective(t);
    return n;
  };
  for (int round = 0; round < 10; ++round) {
    std::vector<std::uint32_t> vertices;
    for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t)
      if (fm.defective(t)) vertices.insert(vertices.end(), mesh.triangles[t].begin(), mesh.triangles[t].end());
    std::sort(vertices.begin(), vertices.end());
    vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
    bool moved = false;
    for (std::uint32_t v : vertices) {
      const std::vector<std::uint32_t> r = region(v);
      const std::size_t before = defects(r);
      if (before == 0) continue;
      std::vector<std::uint32_t> ring;
      for (std::uint32_t t : around[v])
        for (std::uint32_t w : mesh.triangles[t])
          if (w != v) ring.push_back(w);
      std::sort(ring.begin(), ring.end());
      ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
      Vec3d mean{0, 0, 0};
      for (std::uint32_t w : ring) mean = add(mean, divide(toVec3d(mesh.positions[w]), double(ring.size())));
      const Vec3f original = mesh.positions[v];
      // Towards the neighbours' mean first, then towards each neighbour in turn.
      std::vector<Vec3d> goals{mean};
      for (std::uint32_t w : ring) goals.push_back(toVec3d(mesh.positions[w]));
      for (const Vec3d& goal : goals) {
        for (double step : {1.0, 0.5, 0.25}) {
          if (&goal != &goals[0] && step == 1.0) continue;  // onto a neighbour: zero area
          const Vec3d from = toVec3d(original);
          mesh.positions[v] = toVec3f(add(from, scale(sub(goal, from), step)));
          if (defects(r) < before) {
            moved = true;
            break;
          }
          mesh.positions[v] = original;
        }
        if (mesh.positions[v] != original) break;
      }
    }
    if (!moved) break;
  }
  computeVertexNormals(mesh);
  std::size_t left = 0;
  for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t) left += fm.defective(t);
  return left;
}

std::size_t dropCollapsedSpecks(SurfaceMesh& mesh, std::size_t max_triangles) {
  const std::size_t nt = mesh.triangles.size();
  const std::vector<std::uint32_t> piece = pieceOfVertex(mesh);
  std::vector<std::size_t> size(mesh.positions.size(), 0);
  std::vector<char> defective_piece(mesh.positions.size(), 0);
  const FlipMesh fm(mesh);
  for (std::uint32_t t = 0; t < nt; ++t) {
    const std::uint32_t root = piece[mesh.triangles[t][0]];
    ++size[root];
    if (fm.defective(t)) defective_piece[root] = 1;
  }
  std::size_t dropped = 0;
  for (auto& t : mesh.triangles) {
    const std::uint32_t root = piece[t[0]];
    if (defective_piece[root] && size[root] <= max_triangles) {
      t = {t[0], t[0], t[0]};  // dropped by compactMesh()
      ++dropped;
    }
  }
  if (dropped > 0) {
    compactMesh(mesh);
    computeVertexNormals(mesh);
  }
  return dropped;
}

}  // namespace rockbake
