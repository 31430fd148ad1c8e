#include "mesh/simplify_lods.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <unordered_map>
#include <utility>

#include <meshoptimizer.h>
#include <spdlog/spdlog.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_sort.h>

#include "mesh/mesh_defects.h"
#include "mesh/subdivide.h"

namespace rockbake {
namespace {

// Half-edges grouped by undirected edge: (min << 32 | max, corner) pairs,
// sorted, so every face on an edge, in either direction, is one contiguous
// run. Millions of them sort in a fraction of the time a hash map of lists
// takes to build. Corner c stands for its half-edge indices[c] → indices[next(c)].
using HalfEdge = std::pair<std::uint64_t, std::size_t>;

std::size_t nextCorner(std::size_t c) {
  return c - c % 3 + (c % 3 + 1) % 3;
}

std::vector<HalfEdge> halfEdgesByEdge(const std::vector<unsigned int>& indices) {
  std::vector<HalfEdge> edges(indices.size());
  for (std::size_t c = 0; c < indices.size(); ++c) {
    const std::uint64_t a = indices[c], b = indices[nextCorner(c)];
    edges[c] = {(std::min(a, b) << 32) | std::max(a, b), c};
  }
  tbb::parallel_sort(edges.begin(), edges.end());
  return edges;
}

// Calls visit(key, forward, backward) for each undirected edge: the corners of
// its half-edges from the lower vertex to the higher, and back.
template <typename Visit>
void forEachEdge(const std::vector<unsigned int>& indices, Visit&& visit) {
  const std::vector<HalfEdge> edges = halfEdgesByEdge(indices);
  std::vector<std::size_t> forward, backward;
  for (std::size_t i = 0; i < edges.size();) {
    const std::uint64_t key = edges[i].first;
    forward.clear(), backward.clear();
    for (; i < edges.size() && edges[i].first == key; ++i) {
      const std::size_t c = edges[i].second;
      (indices[c] < indices[nextCorner(c)] ? forward : backward).push_back(c);
    }
    visit(key, forward, backward);
  }
}

// Collapsing a thin part can leave two coincident triangles of opposite
// winding glued back to back (each of their edges then has four faces).
// Removing both restores edge-manifoldness; the surface is pinched there, as
// the collapse intended.
void dropSandwiches(std::vector<unsigned int>& indices) {
  const std::size_t n = indices.size() / 3;
  // Triangles by their sorted corners: coincident triangles sit side by side.
  std::vector<std::pair<std::array<unsigned int, 3>, std::size_t>> sorted(n);
  for (std::size_t t = 0; t < n; ++t) {
    std::array<unsigned int, 3> c{indices[3 * t], indices[3 * t + 1], indices[3 * t + 2]};
    std::sort(c.begin(), c.end());
    sorted[t] = {c, t};
  }
  tbb::parallel_sort(sorted.begin(), sorted.end());
  std::vector<char> drop(n, 0);
  bool any = false;
  // Pair them off two by two within a run of equal corners (an odd one out stays).
  for (std::size_t i = 0; i + 1 < n; ++i)
    if (sorted[i].first == sorted[i + 1].first) {
      drop[sorted[i].second] = drop[sorted[i + 1].second] = 1, any = true;
      ++i;
    }
  if (!any) return;
  std::size_t w = 0;
  for (std::size_t t = 0; t < n; ++t)
    if (!drop[t])
      for (int k = 0; k < 3; ++k) indices[w++] = indices[3 * t + k];
  indices.resize(w);
}

// Directed edges whose undirected edge is not used exactly once in each direction.
std::size_t nonManifoldEdges(const std::vector<unsigned int>& indices) {
  std::size_t bad = 0;
  forEachEdge(indices, [&](std::uint64_t, const auto& forward, const auto& backward) {
    if (forward.size() != 1 || backward.size() != 1) bad += !forward.empty() + !backward.empty();
  });
  return bad;
}

// Makes an edge-paired triangle soup manifold by splitting pinched vertices.
// Where an undirected edge carries k faces each way (k > 1: sheets pinched
// onto one edge), each face is paired with its neighbour around the edge
// across the solid between the sheets;
// then the faces around each vertex are grouped into fans joined through those
// pairs, and every fan after the first gets its own copy of the vertex.
// Returns, for each vertex of the result beyond `vertex_count`, the vertex it copies.
std::vector<unsigned int> splitPinches(std::vector<unsigned int>& indices,
                                       const std::vector<std::array<float, 3>>& positions) {
  const std::size_t vertex_count = positions.size();
  const std::size_t corners = indices.size();
  const auto prev = [](std::size_t c) { return c - c % 3 + (c % 3 + 2) % 3; };
  constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();
  std::vector<std::size_t> twin(corners, kNone);
  forEachEdge(indices, [&](std::uint64_t k, const auto& list, const auto& back_list) {
    if (list.size() != back_list.size()) return;  // left open
    if (list.size() == 1) {
      twin[list[0]] = back_list[0], twin[back_list[0]] = list[0];
      return;
    }
    // Sort the faces around the edge by angle; an outgoing face's outward
    // normal turns towards increasing angle, so the solid between two sheets
    // lies between it and the face just before it: pair those.
    const auto& pu = positions[k >> 32];
    const auto& pw = positions[k & 0xffffffffu];
    const std::array<double, 3> d0{double(pw[0]) - pu[0], double(pw[1]) - pu[1], double(pw[2]) - pu[2]};
    const double dl = std::sqrt(d0[0] * d0[0] + d0[1] * d0[1] + d0[2] * d0[2]);
    if (dl == 0) return;
    const std::array<double, 3> d{d0[0] / dl, d0[1] / dl, d0[2] / dl};
    const auto radial = [&](std::size_t c) {  // the face's third vertex, off the axis
      const auto& px = positions[indices[prev(c)]];
      std::array<double, 3> r{double(px[0]) - pu[0], double(px[1]) - pu[1], double(px[2]) - pu[2]};
      const double along = r[0] * d[0] + r[1] * d[1] + r[2] * d[2];
      for (int a = 0; a < 3; ++a) r[a] -= along * d[a];
      return r;
    };
    std::vector<std::pair<double, std::size_t>> around;  // (angle, corner); in-faces marked by the high bit
    const std::array<double, 3> e1 = radial(list[0]);
    const std::array<double, 3> e2{d[1] * e1[2] - d[2] * e1[1], d[2] * e1[0] - d[0] * e1[2],
                                   d[0] * e1[1] - d[1] * e1[0]};
    const auto angle = [&](std::size_t c) {
      const auto r = radial(c);
      return std::atan2(r[0] * e2[0] + r[1] * e2[1] + r[2] * e2[2], r[0] * e1[0] + r[1] * e1[1] + r[2] * e1[2]);
    };
    constexpr std::size_t kIn = std::size_t(1) << 63;
    for (std::size_t c : list) around.push_back({angle(c), c});
    for (std::size_t c : back_list) around.push_back({angle(c), c | kIn});
    std::sort(around.begin(), around.end());
    const std::size_t n = around.size();
    bool alternating = true;
    for (std::size_t i = 0; i < n; ++i)
      alternating &= ((around[i].second & kIn) != 0) != ((around[(i + 1) % n].second & kIn) != 0);
    if (!alternating) return;  // sheets cross: leave it
    for (std::size_t i = 0; i < n; ++i) {
      if (around[i].second & kIn) continue;
      const std::size_t out = around[i].second, in = around[(i + n - 1) % n].second & ~kIn;
      twin[out] = in, twin[in] = out;
    }
  });
  // Union-find over corners: corner c and the corner across prev(c)'s edge share a vertex and a fan.
  std::vector<std::size_t> parent(corners);
  for (std::size_t c = 0; c < corners; ++c) parent[c] = c;
  const auto find = [&](std::size_t c) {
    while (parent[c] != c) c = parent[c] = parent[parent[c]];
    return c;
  };
  for (std::size_t c = 0; c < corners; ++c) {
    const std::size_t t = twin[prev(c)];
    if (t != kNone) parent[find(c)] = find(t);
  }
  std::vector<std::size_t> fan_of_vertex(vertex_count, kNone);  // the root that keeps the vertex
  std::unordered_map<std::size_t, unsigned int> copy_of_root;
  std::vector<unsigned int> copies;
  for (std::size_t c = 0; c < corners; ++c) {
    const unsigned int v = indices[c];
    const std::size_t root = find(c);
    if (fan_of_vertex[v] == kNone) fan_of_vertex[v] = root;
    if (fan_of_vertex[v] == root) continue;
    auto [it, fresh] = copy_of_root.try_emplace(root, unsigned(vertex_count + copies.size()));
    if (fresh) copies.push_back(v);
    indices[c] = it->second;
  }
  return copies;
}

// `m` simplified to about `target_triangles` (at least 4) or until the error
// would pass `max_error` (world units), whichever comes first; `ratio` only for the log.
SurfaceMesh simplify(const SurfaceMesh& m, std::size_t target_triangles, double ratio, double max_error = -1.0) {
  if (m.triangles.empty()) return m;
  const std::size_t index_count = 3 * m.triangles.size();
  const std::size_t target = std::min(std::max<std::size_t>(4, target_triangles) * 3, index_count);
  std::vector<unsigned int> indices(index_count), simplified;
  for (std::size_t t = 0; t < m.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) indices[3 * t + k] = m.triangles[t][k];
  // meshoptimizer does not check the link condition: a collapse can glue two
  // triangles back to back or pinch two sheets onto one edge. Repair both;
  // where the repair cannot pair the faces of an edge, simplify once more to a
  // target 1 % lower, and keep the better result.
  std::vector<unsigned int> copies;
  std::size_t bad = std::numeric_limits<std::size_t>::max();
  const float scale = meshopt_simplifyScale(&m.positions[0][0], m.positions.size(), sizeof(std::array<float, 3>));
  const float relative_error = max_error < 0 || scale <= 0 ? 1.0f : float(max_error / scale);
  for (int attempt = 0; attempt < 2 && bad > 0; ++attempt) {
    const double nudge = attempt == 0 ? 1.0 : 0.99;
    const std::size_t attempt_target =
        std::min(std::max<std::size_t>(4, std::size_t(double(target / 3) * nudge)) * 3, index_count);
    std::vector<unsigned int> result(index_count);
    float error = 0.0f;
    result.resize(meshopt_simplify(result.data(), indices.data(), index_count, &m.positions[0][0], m.positions.size(),
                                   sizeof(std::array<float, 3>), attempt_target, relative_error * float(nudge),
                                   meshopt_SimplifyLockBorder, &error));
    dropSandwiches(result);
    std::vector<unsigned int> result_copies = splitPinches(result, m.positions);
    const std::size_t result_bad = nonManifoldEdges(result);
    spdlog::debug("LOD {} of {}: {} → {} triangles, error {:.2g}, {} pinched vertices split, {} non-manifold edges",
                  ratio, m.name, m.triangles.size(), result.size() / 3, error, result_copies.size(), result_bad);
    if (result_bad < bad) bad = result_bad, simplified = std::move(result), copies = std::move(result_copies);
  }
  if (bad > 0)
    spdlog::warn("LOD {} of the {} surface has {} edges not shared by exactly two faces", ratio, m.name, bad);
  const auto source = [&](std::size_t i) {
    return i < m.positions.size() ? i : std::size_t(copies[i - m.positions.size()]);
  };

  // Keep only the vertices still referenced, in their original order (copies last).
  constexpr std::uint32_t kUnused = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> remap(m.positions.size() + copies.size(), kUnused);
  for (unsigned int i : simplified) remap[i] = 0;
  SurfaceMesh out;
  out.name = m.name;
  for (std::size_t i = 0; i < remap.size(); ++i) {
    if (remap[i] == kUnused) continue;
    remap[i] = std::uint32_t(out.positions.size());
    const std::size_t s = source(i);
    out.positions.push_back(m.positions[s]);
    out.durability.push_back(m.durability[s]);
    out.colluvium.push_back(m.colluvium[s]);
    out.curvature.push_back(m.curvature[s]);
    out.altitude.push_back(m.altitude[s]);
    if (!m.colors.empty()) out.colors.push_back(m.colors[s]);
  }
  out.triangles.reserve(simplified.size() / 3);
  for (std::size_t t = 0; t < simplified.size(); t += 3)
    out.triangles.push_back({remap[simplified[t]], remap[simplified[t + 1]], remap[simplified[t + 2]]});
  // meshoptimizer 0.18 lets a collapse leave a triangle of zero area or one
  // folded against its neighbours; flip and collapse those away.
  if (bad == 0) {
    if (const std::size_t left = repairFoldOvers(out))
      spdlog::warn("LOD {} of the {} surface keeps {} folded or zero-area triangles", ratio, m.name, left);
  } else {
    computeVertexNormals(out);
  }
  return out;
}

}  // namespace

AssetMeshes simplifyToError(const AssetMeshes& meshes, double max_error) {
  AssetMeshes lod0;
  tbb::parallel_invoke([&] { lod0.rock = simplify(meshes.rock, 0, 0.0, max_error); },
                       [&] { lod0.colluvium = simplify(meshes.colluvium, 0, 0.0, max_error); });
  lod0.bounds_min = meshes.bounds_min, lod0.bounds_max = meshes.bounds_max;
  lod0.durability_range = meshes.durability_range;
  return lod0;
}

std::vector<AssetMeshes> simplifyLods(const AssetMeshes& meshes, const LodParams& params) {
  // Each LOD is simplified from the previous one (cheaper than starting from
  // the input every time); targets stay shares of the input. The two surfaces
  // simplify in parallel.
  std::vector<AssetMeshes> lods;
  lods.reserve(params.targets.size());
  const AssetMeshes* from = &meshes;
  const double rock = double(meshes.rock.triangles.size()), colluvium = double(meshes.colluvium.triangles.size());
  const double total = std::max(1.0, rock + colluvium);
  for (double target : params.targets) {
    const double ratio = target >= 1.0 ? target / total : target;
    const auto count = [&](double full) { return std::size_t(std::llround(ratio * full)); };
    if (count(rock) > from->rock.triangles.size() || count(colluvium) > from->colluvium.triangles.size())
      from = &meshes;
    AssetMeshes lod;
    tbb::parallel_invoke([&] { lod.rock = simplify(from->rock, count(rock), ratio); },
                         [&] { lod.colluvium = simplify(from->colluvium, count(colluvium), ratio); });
    lod.bounds_min = meshes.bounds_min, lod.bounds_max = meshes.bounds_max;
    lod.durability_range = meshes.durability_range;
    lods.push_back(std::move(lod));
    from = &lods.back();
  }
  return lods;
}

}  // namespace rockbake
