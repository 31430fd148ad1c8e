#include "mesh/split_non_manifold.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <utility>

#include "geometry/disjoint_set.h"
#include "geometry/edge_table.h"
#include "geometry/vertex_remap.h"
#include "mesh/subdivide.h"

namespace rockbake {
namespace {

constexpr std::uint32_t kNone = EdgeTable::kNone;

// Pairs the outgoing and incoming corners of edge e (k > 1 faces each way).
// Sorted by angle around the edge, an outgoing face's outward normal turns
// towards increasing angle, so the solid between two sheets lies between it
// and the face just before it: those are paired when the directions
// alternate. Sheets that cross, or lie on each other (no angle to sort by):
// any pairing is as good; the fans make it manifold.
void pairAroundEdge(const EdgeTable& edges, std::uint32_t e, std::span<const unsigned int> indices,
                    const std::vector<Vec3f>& positions, std::vector<std::uint32_t>& twin) {
  const Vec3d pu = toVec3d(positions[edges.edge(e).a]);
  const Vec3d d = normalised(sub(toVec3d(positions[edges.edge(e).b]), pu), Vec3d{0, 0, 0});
  const auto radial = [&](std::uint32_t c) {  // the face's third vertex, off the axis
    const Vec3d r = sub(toVec3d(positions[indices[edges.prev(c)]]), pu);
    return sub(r, scale(d, dot(r, d)));
  };
  const Vec3d e1 = radial(edges.forwardCorners(e)[0]);
  const Vec3d e2 = cross(d, e1);
  const auto angle = [&](std::uint32_t c) {
    const Vec3d r = radial(c);
    return std::atan2(dot(r, e2), dot(r, e1));
  };
  constexpr std::uint64_t kIn = std::uint64_t(1) << 63;  // marks an incoming corner
  std::vector<std::pair<double, std::uint64_t>> around;  // (angle, corner)
  for (std::uint32_t c : edges.forwardCorners(e)) around.push_back({angle(c), c});
  for (std::uint32_t c : edges.backwardCorners(e)) around.push_back({angle(c), c | kIn});
  std::sort(around.begin(), around.end());
  const std::size_t n = around.size();
  bool alternating = true;
  for (std::size_t i = 0; i < n; ++i)
    alternating &= ((around[i].second & kIn) != 0) != ((around[(i + 1) % n].second & kIn) != 0);
  if (alternating) {
    for (std::size_t i = 0; i < n; ++i) {
      if (around[i].second & kIn) continue;
      const auto out = std::uint32_t(around[i].second), in = std::uint32_t(around[(i + n - 1) % n].second & ~kIn);
      twin[out] = in, twin[in] = out;
    }
    return;
  }
  std::vector<std::uint32_t> outs, ins;
  for (const auto& [a, c] : around) (c & kIn ? ins : outs).push_back(std::uint32_t(c & ~kIn));
  for (std::size_t i = 0; i < outs.size(); ++i) twin[outs[i]] = ins[i], twin[ins[i]] = outs[i];
}

// The fans: corner c and the corner across prev(c)'s edge share a vertex and a fan.
DisjointSet groupFans(const EdgeTable& edges, const std::vector<std::uint32_t>& twin) {
  DisjointSet fans(twin.size());
  for (std::uint32_t c = 0; c < twin.size(); ++c)
    if (const std::uint32_t t = twin[edges.prev(c)]; t != kNone) fans.unite(c, t);
  return fans;
}

// Re-pairs crosswise the first two pairs of a shared edge whose fans coincide
// at both its ends; true if there were such.
bool repairCrosswise(const EdgeTable& edges, const std::vector<std::uint32_t>& shared, std::vector<std::uint32_t>& twin,
                     DisjointSet& fans) {
  for (std::uint32_t e : shared) {
    const std::span<const std::uint32_t> outs = edges.forwardCorners(e);
    // An outgoing corner sits at the edge's lower vertex, the next one at the higher.
    const auto ends = [&](std::uint32_t out) { return std::pair{fans.find(out), fans.find(edges.next(out))}; };
    for (std::size_t i = 0; i < outs.size(); ++i)
      for (std::size_t j = i + 1; j < outs.size(); ++j)
        if (ends(outs[i]) == ends(outs[j])) {
          const std::uint32_t a = outs[i], b = outs[j], ta = twin[a], tb = twin[b];
          twin[a] = tb, twin[tb] = a, twin[b] = ta, twin[ta] = b;
          return true;
        }
  }
  return false;
}

// Points every fan after the first of its vertex at a new copy of the vertex;
// returns the vertex each copy copies.
std::vector<unsigned int> copyFans(std::vector<unsigned int>& indices, std::size_t vertex_count, DisjointSet& fans) {
  std::vector<std::uint32_t> fan_of_vertex(vertex_count, kNone);  // the fan that keeps the vertex
  std::vector<std::uint32_t> copy_of_fan(indices.size(), kNone);
  std::vector<unsigned int> copies;
  for (std::uint32_t c = 0; c < indices.size(); ++c) {
    const unsigned int v = indices[c];
    const std::uint32_t fan = fans.find(c);
    if (fan_of_vertex[v] == kNone) fan_of_vertex[v] = fan;
    if (fan_of_vertex[v] == fan) continue;
    if (copy_of_fan[fan] == kNone) {
      copy_of_fan[fan] = std::uint32_t(vertex_count + copies.size());
      copies.push_back(v);
    }
    indices[c] = copy_of_fan[fan];
  }
  return copies;
}

}  // namespace

std::vector<unsigned int> splitPinches(std::vector<unsigned int>& indices, const std::vector<Vec3f>& positions) {
  const EdgeTable edges(indices);
  std::vector<std::uint32_t> twin(edges.twins().begin(), edges.twins().end());
  std::vector<std::uint32_t> shared;  // edges with k > 1 faces each way
  std::size_t rounds = 0;             // a bound on the re-pairings
  for (std::uint32_t e = 0; e < edges.edges().size(); ++e) {
    const EdgeTable::Edge& edge = edges.edge(e);
    if (edge.forward != edge.backward || edge.forward < 2) continue;  // left open, or paired already
    shared.push_back(e);
    rounds += edge.forward;
    pairAroundEdge(edges, e, indices, positions, twin);
  }
  // One crosswise re-pairing per regrouping: each splits fans, so it ends
  // (a re-pairing decided on stale fans could join two instead). Where an
  // edge was left open, fans are not closed loops; the bound holds there.
  DisjointSet fans = groupFans(edges, twin);
  for (; rounds > 0 && repairCrosswise(edges, shared, twin, fans); --rounds) fans = groupFans(edges, twin);
  return copyFans(indices, positions.size(), fans);
}

std::size_t splitNonManifold(SurfaceMesh& mesh) {
  requireVertexArrays(mesh);  // before a triangle is pointed at a copy
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

}  // namespace rockbake
