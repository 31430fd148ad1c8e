#include "mesh/simplify_lods.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <unordered_map>
#include <utility>

#include <meshoptimizer.h>
#include <spdlog/spdlog.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_sort.h>

#include "core/disjoint_set.h"
#include "core/vec3.h"
#include "core/vertex_remap.h"
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
// the collapse intended. Returns the vertices of the removed triangles.
std::vector<unsigned int> dropSandwiches(std::vector<unsigned int>& indices) {
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
  std::vector<unsigned int> dropped;
  // Within a run of equal corners, pair each triangle with the next one of
  // opposite winding (what is left stays): dropping two of the same winding
  // would leave their edges with more faces one way than the other, open.
  const auto ascending = [&](std::size_t t) {  // winds through its corners in increasing order
    const unsigned int a = indices[3 * t], b = indices[3 * t + 1], c = indices[3 * t + 2];
    return (a < b) + (b < c) + (c < a) == 2;
  };
  for (std::size_t i = 0; i < n;) {
    std::size_t j = i + 1;
    while (j < n && sorted[j].first == sorted[i].first) ++j;
    for (std::size_t a = i; a + 1 < j; ++a) {
      const std::size_t ta = sorted[a].second;
      if (drop[ta]) continue;
      for (std::size_t b = a + 1; b < j; ++b) {
        const std::size_t tb = sorted[b].second;
        if (drop[tb] || ascending(ta) == ascending(tb)) continue;
        drop[ta] = drop[tb] = 1;
        dropped.insert(dropped.end(), sorted[i].first.begin(), sorted[i].first.end());
        break;
      }
    }
    i = j;
  }
  if (dropped.empty()) return dropped;
  std::size_t w = 0;
  for (std::size_t t = 0; t < n; ++t)
    if (!drop[t])
      for (int k = 0; k < 3; ++k) indices[w++] = indices[3 * t + k];
  indices.resize(w);
  return dropped;
}

// Directed edges whose undirected edge is not used exactly once in each direction.
std::size_t nonManifoldEdges(const std::vector<unsigned int>& indices) {
  std::size_t bad = 0;
  forEachEdge(indices, [&](std::uint64_t, const auto& forward, const auto& backward) {
    if (forward.size() != 1 || backward.size() != 1) bad += !forward.empty() + !backward.empty();
  });
  return bad;
}

// Makes an edge-paired triangle soup manifold by splitting vertices.
// Where an undirected edge carries k faces each way (k > 1: sheets touching
// along the edge, or pinched onto it), each outgoing face is paired with an
// incoming one: its neighbour around the edge across the solid between the
// sheets when the faces alternate in direction around it, else the faces in
// angle order. The faces around each vertex are then grouped into fans joined
// through those pairs. Two pairs of one edge whose fans coincide at both its
// ends would still share the edge after the split (the sheets meet there and
// again elsewhere around both vertices): re-pairing them crosswise splits the
// fan at each end in two, one pair in each, so it is done until none is left.
// Every fan after the first of its vertex then gets its own copy of the vertex.
// Returns, for each vertex of the result beyond `vertex_count`, the vertex it copies.
std::vector<unsigned int> splitPinches(std::vector<unsigned int>& indices,
                                       const std::vector<std::array<float, 3>>& positions) {
  const std::size_t vertex_count = positions.size();
  const std::size_t corners = indices.size();
  const auto prev = [](std::size_t c) { return c - c % 3 + (c % 3 + 2) % 3; };
  constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();
  std::vector<std::size_t> twin(corners, kNone);
  std::vector<std::vector<std::size_t>> shared;  // per edge with k > 1: its outgoing corners
  forEachEdge(indices, [&](std::uint64_t k, const auto& list, const auto& back_list) {
    if (list.size() != back_list.size()) return;  // left open
    if (list.size() == 1) {
      twin[list[0]] = back_list[0], twin[back_list[0]] = list[0];
      return;
    }
    shared.push_back(list);
    // Sort the faces around the edge by angle; an outgoing face's outward
    // normal turns towards increasing angle, so the solid between two sheets
    // lies between it and the face just before it: pair those.
    const Vec3d pu = toVec3d(positions[k >> 32]);
    const Vec3d d = normalised(sub(toVec3d(positions[k & 0xffffffffu]), pu), Vec3d{0, 0, 0});
    const auto radial = [&](std::size_t c) {  // the face's third vertex, off the axis
      const Vec3d r = sub(toVec3d(positions[indices[prev(c)]]), pu);
      return sub(r, scale(d, dot(r, d)));
    };
    std::vector<std::pair<double, std::size_t>> around;  // (angle, corner); in-faces marked by the high bit
    const Vec3d e1 = radial(list[0]);
    const Vec3d e2 = cross(d, e1);
    const auto angle = [&](std::size_t c) {
      const Vec3d r = radial(c);
      return std::atan2(dot(r, e2), dot(r, e1));
    };
    constexpr std::size_t kIn = std::size_t(1) << 63;
    for (std::size_t c : list) around.push_back({angle(c), c});
    for (std::size_t c : back_list) around.push_back({angle(c), c | kIn});
    std::sort(around.begin(), around.end());
    const std::size_t n = around.size();
    bool alternating = true;
    for (std::size_t i = 0; i < n; ++i)
      alternating &= ((around[i].second & kIn) != 0) != ((around[(i + 1) % n].second & kIn) != 0);
    if (alternating) {
      for (std::size_t i = 0; i < n; ++i) {
        if (around[i].second & kIn) continue;
        const std::size_t out = around[i].second, in = around[(i + n - 1) % n].second & ~kIn;
        twin[out] = in, twin[in] = out;
      }
      return;
    }
    // Sheets that cross, or lie on each other (no angle to sort by): any
    // pairing is as good; the fans below make it manifold.
    std::vector<std::size_t> outs, ins;
    for (const auto& [a, c] : around) (c & kIn ? ins : outs).push_back(c & ~kIn);
    for (std::size_t i = 0; i < outs.size(); ++i) twin[outs[i]] = ins[i], twin[ins[i]] = outs[i];
  });
  // The fans: corner c and the corner across prev(c)'s edge share a vertex and a fan.
  DisjointSet fans(corners);
  const auto find = [&](std::size_t c) { return fans.find(std::uint32_t(c)); };
  const auto group = [&] {
    fans = DisjointSet(corners);
    for (std::size_t c = 0; c < corners; ++c) {
      const std::size_t t = twin[prev(c)];
      if (t != kNone) fans.unite(std::uint32_t(c), std::uint32_t(t));
    }
  };
  // One crosswise re-pairing per regrouping: each splits fans, so it ends
  // (a re-pairing decided on stale fans could join two instead). Where an
  // edge was left open, fans are not closed loops; the bound holds there.
  std::size_t rounds = 0;
  for (const auto& outs : shared) rounds += outs.size();
  for (group(); rounds > 0; --rounds, group()) {
    bool repaired = false;
    for (std::size_t e = 0; e < shared.size() && !repaired; ++e) {
      const auto& outs = shared[e];
      // An outgoing corner sits at the edge's lower vertex, the next one at the higher.
      const auto ends = [&](std::size_t out) { return std::pair{find(out), find(nextCorner(out))}; };
      for (std::size_t i = 0; i < outs.size() && !repaired; ++i)
        for (std::size_t j = i + 1; j < outs.size() && !repaired; ++j)
          if (ends(outs[i]) == ends(outs[j])) {
            const std::size_t a = outs[i], b = outs[j], ta = twin[a], tb = twin[b];
            twin[a] = tb, twin[tb] = a, twin[b] = ta, twin[ta] = b;
            repaired = true;
          }
    }
    if (!repaired) break;
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

using Point = std::array<float, 3>;

// One simplification pass: the unlocked triangles simplified with their
// border (where they meet the locked ones) held in place, the locked ones kept
// as they are, then the simplifier's damage repaired as far as it can be.
struct Pass {
  SurfaceMesh mesh;
  std::size_t bad_edges = 0;   // edges not shared by exactly two faces after the repair
  std::vector<Point> torn;     // vertices of those edges
  std::vector<Point> cut;      // pinches that cut the surface in two
  std::vector<Point> folded;   // vertices of fold-overs and zero-area triangles the repair left
  std::size_t folds_left = 0;  // how many such triangles
};

Pass simplifyPass(const SurfaceMesh& m, const std::vector<unsigned int>& indices, const std::vector<char>& locked,
                  std::size_t target_indices, float relative_error, std::size_t level) {
  std::vector<unsigned int> free, kept;
  for (std::size_t t = 0; t < locked.size(); ++t)
    (locked[t] ? kept : free).insert((locked[t] ? kept : free).end(), &indices[3 * t], &indices[3 * t] + 3);
  const std::size_t free_target =
      std::min(free.size(), target_indices > kept.size() + 12 ? target_indices - kept.size() : std::size_t(12));
  std::vector<unsigned int> result(free.size());
  float error = 0.0f;
  result.resize(meshopt_simplify(result.data(), free.data(), free.size(), &m.positions[0][0], m.positions.size(),
                                 sizeof(Point), free_target, relative_error, meshopt_SimplifyLockBorder, &error));
  result.insert(result.end(), kept.begin(), kept.end());

  Pass pass;
  const std::vector<unsigned int> glued = dropSandwiches(result);
  const std::vector<unsigned int> copies = splitPinches(result, m.positions);
  pass.bad_edges = nonManifoldEdges(result);
  spdlog::debug(
      "LOD{} of {}: {} → {} triangles ({} locked), error {:.2g}, {} pinched vertices split, {} glued, "
      "{} non-manifold edges",
      level, m.name, m.triangles.size(), result.size() / 3, kept.size() / 3, error, copies.size(), glued.size() / 3,
      pass.bad_edges);
  // A pinch whose split leaves the copy and its vertex in different pieces cut
  // the surface in two (a neck collapsed to a point); other pinches, and glued
  // pairs, only change the genus or seal a slot thinner than the error.
  if (!copies.empty()) {
    DisjointSet pieces(m.positions.size() + copies.size());
    for (std::size_t t = 0; t < result.size(); t += 3)
      pieces.unite(result[t], result[t + 1]), pieces.unite(result[t], result[t + 2]);
    for (std::size_t j = 0; j < copies.size(); ++j)
      if (!pieces.connected(std::uint32_t(m.positions.size() + j), copies[j]))
        pass.cut.push_back(m.positions[copies[j]]);
  }

  // Keep only the vertices still referenced, in their original order (copies
  // last), with every per-vertex value (normals are recomputed below).
  std::vector<std::uint32_t> remap(m.positions.size() + copies.size(), kDroppedVertex), source;
  for (unsigned int i : result) remap[i] = 0;
  for (std::uint32_t i = 0; i < remap.size(); ++i) {
    if (remap[i] == kDroppedVertex) continue;
    remap[i] = std::uint32_t(source.size());
    source.push_back(i < m.positions.size() ? i : copies[i - m.positions.size()]);
  }
  SurfaceMesh& out = pass.mesh;
  out = gatherVertices(m, source);
  out.triangles.reserve(result.size() / 3);
  for (std::size_t t = 0; t < result.size(); t += 3)
    out.triangles.push_back({remap[result[t]], remap[result[t + 1]], remap[result[t + 2]]});
  // meshoptimizer 0.18 lets a collapse leave a triangle of zero area or one
  // folded against its neighbours; flip and collapse those away (the repair
  // needs every edge paired).
  if (pass.bad_edges == 0)
    repairFoldOvers(out);
  else
    computeVertexNormals(out);
  const MeshDefects d = checkMesh(out);
  pass.folds_left = d.fold_overs + d.zero_area;
  for (std::uint32_t v : d.open_edge_vertices) pass.torn.push_back(out.positions[v]);
  if (pass.bad_edges == 0)
    for (std::uint32_t v : d.defect_vertices) pass.folded.push_back(out.positions[v]);
  return pass;
}

// Locks every triangle of `m` with a vertex within `radius` of a trouble point
// (a hash grid of the points, cells `radius` wide).
void lockAround(const SurfaceMesh& m, const std::vector<Point>& trouble, double radius, std::vector<char>& locked) {
  const auto cell = [&](const Point& p) {
    return std::array<std::int64_t, 3>{std::int64_t(std::floor(p[0] / radius)), std::int64_t(std::floor(p[1] / radius)),
                                       std::int64_t(std::floor(p[2] / radius))};
  };
  const auto key = [](const std::array<std::int64_t, 3>& c) {
    return std::uint64_t(c[0] * 73856093) ^ std::uint64_t(c[1] * 19349663) ^ std::uint64_t(c[2] * 83492791);
  };
  std::unordered_map<std::uint64_t, std::vector<Point>> grid;
  for (const Point& p : trouble) grid[key(cell(p))].push_back(p);
  std::vector<char> near(m.positions.size(), 0);
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    const Point& p = m.positions[v];
    const auto c = cell(p);
    for (int dx = -1; dx <= 1 && !near[v]; ++dx)
      for (int dy = -1; dy <= 1 && !near[v]; ++dy)
        for (int dz = -1; dz <= 1 && !near[v]; ++dz) {
          const auto it = grid.find(key({c[0] + dx, c[1] + dy, c[2] + dz}));
          if (it == grid.end()) continue;
          for (const Point& q : it->second) {
            if (distanceSquared(toVec3d(p), toVec3d(q)) <= radius * radius) {
              near[v] = 1;
              break;
            }
          }
        }
  }
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    const auto& tri = m.triangles[t];
    if (near[tri[0]] || near[tri[1]] || near[tri[2]]) locked[t] = 1;
  }
}

double meanEdgeLength(const SurfaceMesh& m) {
  double sum = 0;
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k) sum += length(sub(toVec3d(m.positions[t[k]]), toVec3d(m.positions[t[(k + 1) % 3]])));
  return m.triangles.empty() ? 0.0 : sum / double(3 * m.triangles.size());
}

// A piece this small that the simplifier folded flat is a speck of debris, dropped from a budgeted LOD.
constexpr std::size_t kSpeckTriangles = 24;

// Moves vertices of what the repair left towards their neighbours, drops
// specks still folded, and counts again.
void relaxLeftovers(Pass& pass) {
  if (relaxFoldOvers(pass.mesh) > 0) dropCollapsedSpecks(pass.mesh, kSpeckTriangles);
  const MeshDefects d = checkMesh(pass.mesh);
  pass.folds_left = d.fold_overs + d.zero_area;
  pass.folded.clear();
  for (std::uint32_t v : d.defect_vertices) pass.folded.push_back(pass.mesh.positions[v]);
}

// `m` simplified to about `target_triangles` (at least 4) or until the error
// would pass `max_error` (world units), whichever comes first; `level` (the LOD's number) only for the log.
// meshoptimizer does not check the link condition: a collapse can glue two
// triangles back to back, pinch two sheets together, tear an edge open or fold
// a triangle over. Each pass repairs what it can; see the loop for where
// triangles are then locked (kept as they are) and the rest simplified again.
// The cleanest pass is kept.
SurfaceMesh simplify(const SurfaceMesh& m, std::size_t target_triangles, std::size_t level, double max_error = -1.0) {
  if (m.triangles.empty()) return m;
  const std::size_t index_count = 3 * m.triangles.size();
  const std::size_t target = std::min(std::max<std::size_t>(4, target_triangles) * 3, index_count);
  std::vector<unsigned int> indices(index_count);
  for (std::size_t t = 0; t < m.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) indices[3 * t + k] = m.triangles[t][k];
  const float scale = meshopt_simplifyScale(&m.positions[0][0], m.positions.size(), sizeof(Point));
  const float relative_error = max_error < 0 || scale <= 0 ? 1.0f : float(max_error / scale);

  // Defects the input already has are not the simplifier's doing.
  const MeshDefects input = checkMesh(m);
  std::vector<Point> inherited;
  for (std::uint32_t v : input.defect_vertices) inherited.push_back(m.positions[v]);
  std::sort(inherited.begin(), inherited.end());

  // Error-bounded (LOD0): lock around every tear, cut and new fold and
  // simplify the rest again, the locked neighbourhood doubling each pass.
  // Triangle budgets (further LODs): locking spends the budget, so first aim a
  // little lower or higher (1 %, 2 % either way), and lock only around tears
  // still left after that. A tear outweighs any number of cuts, a cut any
  // number of folds.
  const bool budget = max_error < 0;
  constexpr int kPasses = 7;
  constexpr std::array<double, kPasses> kNudge{1.0, 0.99, 1.01, 0.98, 1.02, 1.0, 1.0};
  std::vector<char> locked(m.triangles.size(), 0);
  std::optional<Pass> best;
  std::size_t best_score = std::numeric_limits<std::size_t>::max();
  double radius = 2.0 * meanEdgeLength(m);
  for (int attempt = 0; attempt < kPasses; ++attempt) {
    const std::size_t pass_target =
        budget ? std::min(std::max<std::size_t>(4, std::size_t(double(target / 3) * kNudge[attempt])) * 3, index_count)
               : target;
    Pass pass = simplifyPass(m, indices, locked, pass_target, relative_error, level);
    // A budget has no error bound to keep: what the repair left is relaxed away before the passes are compared.
    if (budget && pass.bad_edges == 0 && pass.folds_left > 0) relaxLeftovers(pass);
    std::vector<Point> folds;
    for (const Point& p : pass.folded)
      if (!std::binary_search(inherited.begin(), inherited.end(), p)) folds.push_back(p);
    const std::size_t score = 1000000 * pass.bad_edges + 1000 * pass.cut.size() + folds.size();
    std::vector<Point> lock_around = pass.torn;
    if (!budget) {
      lock_around.insert(lock_around.end(), pass.cut.begin(), pass.cut.end());
      lock_around.insert(lock_around.end(), folds.begin(), folds.end());
    }
    if (score < best_score) best_score = score, best = std::move(pass);
    if (score == 0) break;
    if (budget && (attempt < 4 || best->bad_edges == 0)) continue;
    if (lock_around.empty()) {
      if (budget) continue;
      break;  // nothing to lock around
    }
    lockAround(m, lock_around, radius, locked);
    radius *= 2.0;
  }
  if (best->bad_edges > 0) {
    spdlog::warn("LOD{} of the {} surface has {} edges not shared by exactly two faces", level, m.name,
                 best->bad_edges);
  } else if (best->folds_left > 0) {
    spdlog::warn("LOD{} of the {} surface keeps {} folded or zero-area triangles", level, m.name, best->folds_left);
  }
  return std::move(best->mesh);
}

}  // namespace

std::size_t splitNonManifold(SurfaceMesh& mesh) {
  std::vector<unsigned int> indices;
  indices.reserve(3 * mesh.triangles.size());
  for (const auto& t : mesh.triangles) indices.insert(indices.end(), t.begin(), t.end());
  const std::vector<unsigned int> copies = splitPinches(indices, mesh.positions);
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) mesh.triangles[t][k] = indices[3 * t + k];
  appendVertexCopies(mesh, copies);
  computeVertexNormals(mesh);
  return copies.size();
}

AssetMeshes simplifyToError(const AssetMeshes& meshes, double max_error) {
  AssetMeshes lod0;
  tbb::parallel_invoke([&] { lod0.rock = simplify(meshes.rock, 0, 0, max_error); },
                       [&] { lod0.colluvium = simplify(meshes.colluvium, 0, 0, max_error); });
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
    const std::size_t level = lods.size() + 1;
    tbb::parallel_invoke([&] { lod.rock = simplify(from->rock, count(rock), level); },
                         [&] { lod.colluvium = simplify(from->colluvium, count(colluvium), level); });
    lod.bounds_min = meshes.bounds_min, lod.bounds_max = meshes.bounds_max;
    lod.durability_range = meshes.durability_range;
    lods.push_back(std::move(lod));
    from = &lods.back();
  }
  return lods;
}

}  // namespace rockbake
