#include "mesh/mesh_checks.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <utility>
#include <vector>

#include "mesh/extract_surfaces.h"

namespace rockbake {
namespace {

using Vec = std::array<double, 3>;

Vec sub(const std::array<float, 3>& a, const std::array<float, 3>& b) {
  return {double(a[0]) - b[0], double(a[1]) - b[1], double(a[2]) - b[2]};
}
Vec cross(const Vec& a, const Vec& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const Vec& a, const Vec& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

}  // namespace

MeshDefects checkMesh(const SurfaceMesh& m) {
  MeshDefects d;
  const std::size_t nt = m.triangles.size();
  if (nt == 0) return d;
  std::vector<Vec> normal(nt);
  for (std::size_t t = 0; t < nt; ++t) {
    const auto& tri = m.triangles[t];
    const Vec e0 = sub(m.positions[tri[1]], m.positions[tri[0]]);
    const Vec e1 = sub(m.positions[tri[2]], m.positions[tri[0]]);
    const Vec e2 = sub(m.positions[tri[2]], m.positions[tri[1]]);
    normal[t] = cross(e0, e1);
    const double longest = std::max({dot(e0, e0), dot(e1, e1), dot(e2, e2)});
    // |cross| is twice the area; zero area relative to the triangle's own size.
    if (std::sqrt(dot(normal[t], normal[t])) <= 2e-6 * longest) ++d.zero_area;
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
  }
  // Components through shared vertices (union-find).
  std::vector<std::uint32_t> parent(m.positions.size());
  std::iota(parent.begin(), parent.end(), 0u);
  const auto find = [&](std::uint32_t v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  std::vector<char> used(m.positions.size(), 0);
  for (const auto& t : m.triangles) {
    for (int k = 0; k < 3; ++k) used[t[k]] = 1;
    parent[find(t[1])] = find(t[0]), parent[find(t[2])] = find(t[0]);
  }
  for (std::uint32_t v = 0; v < parent.size(); ++v) d.components += used[v] && find(v) == v;
  d.volume = signedVolume(m);
  return d;
}

}  // namespace rockbake
