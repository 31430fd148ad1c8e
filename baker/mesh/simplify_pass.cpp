#include "mesh/simplify_pass.h"

#include <algorithm>
#include <cstdint>

#include <meshoptimizer.h>
#include <spdlog/spdlog.h>

#include "geometry/disjoint_set.h"
#include "geometry/edge_table.h"
#include "geometry/vertex_remap.h"
#include "mesh/back_to_back.h"
#include "mesh/fold_over_repair.h"
#include "mesh/mesh_defects.h"
#include "mesh/split_non_manifold.h"
#include "mesh/subdivide.h"

namespace rockbake {
namespace {

// meshoptimizer on the unlocked triangles (their border locked), the locked
// ones appended as they are.
std::vector<unsigned int> simplifyUnlocked(const SurfaceMesh& m, const std::vector<unsigned int>& indices,
                                           const std::vector<char>& locked, std::size_t target_indices,
                                           float relative_error, std::size_t& kept_triangles, float& error) {
  std::vector<unsigned int> free, kept;
  for (std::size_t t = 0; t < locked.size(); ++t)
    (locked[t] ? kept : free).insert((locked[t] ? kept : free).end(), &indices[3 * t], &indices[3 * t] + 3);
  const std::size_t free_target =
      std::min(free.size(), target_indices > kept.size() + 12 ? target_indices - kept.size() : std::size_t(12));
  std::vector<unsigned int> result(free.size());
  result.resize(meshopt_simplify(result.data(), free.data(), free.size(), &m.positions[0][0], m.positions.size(),
                                 sizeof(Vec3f), free_target, relative_error, meshopt_SimplifyLockBorder, &error));
  result.insert(result.end(), kept.begin(), kept.end());
  kept_triangles = kept.size() / 3;
  return result;
}

// Directions of edges not used exactly once each way: each such edge counts
// once for each direction it is used in.
std::size_t unpairedEdgeDirections(const std::vector<unsigned int>& indices) {
  std::size_t bad = 0;
  const EdgeTable table(indices);
  for (const EdgeTable::Edge& e : table.edges())
    if (!e.paired()) bad += (e.forward > 0) + (e.backward > 0);
  return bad;
}

// A pinch whose split leaves the copy and its vertex in different pieces cut
// the surface in two (a neck collapsed to a point); other pinches, and glued
// pairs, only change the genus or seal a slot thinner than the error.
std::vector<Vec3f> cutsOf(const SurfaceMesh& m, const std::vector<unsigned int>& result,
                          const std::vector<unsigned int>& copies) {
  std::vector<Vec3f> cut;
  if (copies.empty()) return cut;
  DisjointSet pieces(m.positions.size() + copies.size());
  for (std::size_t t = 0; t < result.size(); t += 3)
    pieces.unite(result[t], result[t + 1]), pieces.unite(result[t], result[t + 2]);
  for (std::size_t j = 0; j < copies.size(); ++j)
    if (!pieces.connected(std::uint32_t(m.positions.size() + j), copies[j])) cut.push_back(m.positions[copies[j]]);
  return cut;
}

// The vertices `result` still uses, in their order (copies last, each with its
// original's values in every per-vertex array), and its triangles.
SurfaceMesh keptVertices(const SurfaceMesh& m, const std::vector<unsigned int>& result,
                         const std::vector<unsigned int>& copies) {
  std::vector<std::uint32_t> remap(m.positions.size() + copies.size(), kDroppedVertex), source;
  for (unsigned int i : result) remap[i] = 0;
  for (std::uint32_t i = 0; i < remap.size(); ++i) {
    if (remap[i] == kDroppedVertex) continue;
    remap[i] = std::uint32_t(source.size());
    source.push_back(i < m.positions.size() ? i : copies[i - m.positions.size()]);
  }
  SurfaceMesh out = gatherVertices(m, source);
  out.triangles.reserve(result.size() / 3);
  for (std::size_t t = 0; t < result.size(); t += 3)
    out.triangles.push_back({remap[result[t]], remap[result[t + 1]], remap[result[t + 2]]});
  return out;
}

}  // namespace

SimplifyPass simplifyPass(const SurfaceMesh& m, const std::vector<unsigned int>& indices,
                          const std::vector<char>& locked, std::size_t target_indices, float relative_error,
                          std::size_t level) {
  std::size_t kept = 0;
  float error = 0.0f;
  std::vector<unsigned int> result = simplifyUnlocked(m, indices, locked, target_indices, relative_error, kept, error);
  SimplifyPass pass;
  const std::vector<unsigned int> glued = dropBackToBackPairs(result);
  const std::vector<unsigned int> copies = splitPinches(result, m.positions);
  pass.bad_edges = unpairedEdgeDirections(result);
  spdlog::debug(
      "LOD{} of {}: {} → {} triangles ({} locked), error {:.2g}, {} pinched vertices split, {} glued, "
      "{} non-manifold edges",
      level, m.name, m.triangles.size(), result.size() / 3, kept, error, copies.size(), glued.size() / 3,
      pass.bad_edges);
  pass.cut = cutsOf(m, result, copies);
  pass.mesh = keptVertices(m, result, copies);
  // meshoptimizer 0.18 lets a collapse leave a triangle of zero area or one
  // folded against its neighbours; flip and collapse those away (the repair
  // needs every edge paired).
  if (pass.bad_edges == 0)
    repairFoldOvers(pass.mesh);
  else
    computeVertexNormals(pass.mesh);
  const MeshDefects d = checkMesh(pass.mesh);
  pass.folds_left = d.fold_overs + d.zero_area;
  for (std::uint32_t v : d.open_edge_vertices) pass.torn.push_back(pass.mesh.positions[v]);
  if (pass.bad_edges == 0)
    for (std::uint32_t v : d.defect_vertices) pass.folded.push_back(pass.mesh.positions[v]);
  return pass;
}

}  // namespace rockbake
