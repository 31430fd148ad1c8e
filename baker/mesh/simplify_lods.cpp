#include "mesh/simplify_lods.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <unordered_map>
#include <utility>

#include <fmt/format.h>
#include <meshoptimizer.h>
#include <spdlog/spdlog.h>
#include <tbb/parallel_for.h>

#include "core/vec3.h"
#include "mesh/collapsed_specks.h"
#include "mesh/mesh_defects.h"
#include "mesh/relax_fold_overs.h"
#include "mesh/simplify_pass.h"
#include "platform/side_by_side.h"

namespace rockbake {
namespace {

// Locks every triangle of `m` with a vertex within `radius` of a trouble point
// (a hash grid of the points, cells `radius` wide).
void lockAround(const SurfaceMesh& m, const std::vector<Vec3f>& trouble, double radius, std::vector<char>& locked) {
  const auto cell = [&](const Vec3f& p) {
    return std::array<std::int64_t, 3>{std::int64_t(std::floor(p[0] / radius)), std::int64_t(std::floor(p[1] / radius)),
                                       std::int64_t(std::floor(p[2] / radius))};
  };
  const auto key = [](const std::array<std::int64_t, 3>& c) {
    return std::uint64_t(c[0] * 73856093) ^ std::uint64_t(c[1] * 19349663) ^ std::uint64_t(c[2] * 83492791);
  };
  std::unordered_map<std::uint64_t, std::vector<Vec3f>> grid;
  for (const Vec3f& p : trouble) grid[key(cell(p))].push_back(p);
  std::vector<char> near(m.positions.size(), 0);
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    const Vec3f& p = m.positions[v];
    const auto c = cell(p);
    for (int dx = -1; dx <= 1 && !near[v]; ++dx)
      for (int dy = -1; dy <= 1 && !near[v]; ++dy)
        for (int dz = -1; dz <= 1 && !near[v]; ++dz) {
          const auto it = grid.find(key({c[0] + dx, c[1] + dy, c[2] + dz}));
          if (it == grid.end()) continue;
          for (const Vec3f& q : it->second) {
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
void relaxLeftovers(SimplifyPass& pass) {
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
// The surface's unrepaired defect, if any ("" when clean).
struct Simplified {
  SurfaceMesh mesh;
  std::string warning;
};

Simplified simplify(const SurfaceMesh& m, std::size_t target_triangles, std::size_t level, double max_error = -1.0) {
  if (m.triangles.empty()) return {m, {}};
  const std::size_t index_count = 3 * m.triangles.size();
  const std::size_t target = std::min(std::max<std::size_t>(4, target_triangles) * 3, index_count);
  std::vector<unsigned int> indices(index_count);
  for (std::size_t t = 0; t < m.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) indices[3 * t + k] = m.triangles[t][k];
  const float scale = meshopt_simplifyScale(&m.positions[0][0], m.positions.size(), sizeof(Vec3f));
  const float relative_error = max_error < 0 || scale <= 0 ? 1.0f : float(max_error / scale);

  // Defects the input already has are not the simplifier's doing.
  const MeshDefects input = checkMesh(m);
  std::vector<Vec3f> inherited;
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
  std::optional<SimplifyPass> best;
  std::size_t best_score = std::numeric_limits<std::size_t>::max();
  double radius = 2.0 * meanEdgeLength(m);
  const auto runPass = [&](int attempt) {
    const std::size_t pass_target =
        budget ? std::min(std::max<std::size_t>(4, std::size_t(double(target / 3) * kNudge[attempt])) * 3, index_count)
               : target;
    SimplifyPass pass = simplifyPass(m, indices, locked, pass_target, relative_error, level);
    // A budget has no error bound to keep: what the repair left is relaxed away before the passes are compared.
    if (budget && pass.bad_edges == 0 && pass.folds_left > 0) relaxLeftovers(pass);
    return pass;
  };
  // A budget's nudged passes lock nothing, so they do not depend on each other: once the first is not clean, the
  // other four run side by side, and are weighed below in order as if made one after another.
  constexpr int kNudged = 5;
  std::array<std::optional<SimplifyPass>, kNudged> nudged;
  for (int attempt = 0; attempt < kPasses; ++attempt) {
    if (budget && attempt == 1) tbb::parallel_for(1, kNudged, [&](int a) { nudged[std::size_t(a)] = runPass(a); });
    SimplifyPass pass =
        budget && attempt >= 1 && attempt < kNudged ? std::move(*nudged[std::size_t(attempt)]) : runPass(attempt);
    std::vector<Vec3f> folds;
    for (const Vec3f& p : pass.folded)
      if (!std::binary_search(inherited.begin(), inherited.end(), p)) folds.push_back(p);
    const std::size_t score = 1000000 * pass.bad_edges + 1000 * pass.cut.size() + folds.size();
    std::vector<Vec3f> lock_around = pass.torn;
    if (!budget) {
      lock_around.insert(lock_around.end(), pass.cut.begin(), pass.cut.end());
      lock_around.insert(lock_around.end(), folds.begin(), folds.end());
    }
    if (score < best_score) best_score = score, best = std::move(pass);
    if (score == 0) break;
    if (budget && attempt < kNudged - 1) continue;
    // Past the nudges a budget locks only around tears: with none, every pass
    // left would repeat one already made (the same target and locks).
    if (budget && best->bad_edges == 0) break;
    if (lock_around.empty()) {
      if (budget) continue;
      break;  // nothing to lock around
    }
    lockAround(m, lock_around, radius, locked);
    radius *= 2.0;
  }
  std::string warning;
  if (best->bad_edges > 0)
    warning = fmt::format("LOD{} of the {} surface has {} edges not shared by exactly two faces", level, m.name,
                          best->bad_edges);
  else if (best->folds_left > 0)
    warning =
        fmt::format("LOD{} of the {} surface keeps {} folded or zero-area triangles", level, m.name, best->folds_left);
  return {std::move(best->mesh), std::move(warning)};
}

// Both surfaces of one level side by side; their warnings reported in surface order.
AssetMeshes simplifyLevel(const AssetMeshes& from, std::size_t rock_target, std::size_t colluvium_target,
                          std::size_t level, double max_error, SimplifyWarnings* warnings) {
  Simplified rock, colluvium;
  sideBySide([&] { rock = simplify(from.rock, rock_target, level, max_error); },
             [&] { colluvium = simplify(from.colluvium, colluvium_target, level, max_error); });
  for (const std::string* w : {&rock.warning, &colluvium.warning}) {
    if (w->empty()) continue;
    if (warnings)
      warnings->push_back(*w);
    else
      spdlog::warn("{}", *w);
  }
  AssetMeshes out;
  out.rock = std::move(rock.mesh);
  out.colluvium = std::move(colluvium.mesh);
  return out;
}

}  // namespace

AssetMeshes simplifyToError(const AssetMeshes& meshes, double max_error, SimplifyWarnings* warnings) {
  AssetMeshes lod0 = simplifyLevel(meshes, 0, 0, 0, max_error, warnings);
  lod0.bounds_min = meshes.bounds_min, lod0.bounds_max = meshes.bounds_max;
  lod0.durability_range = meshes.durability_range;
  return lod0;
}

std::vector<AssetMeshes> simplifyLods(const AssetMeshes& meshes, const LodParams& params, SimplifyWarnings* warnings) {
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
    const std::size_t level = lods.size() + 1;
    AssetMeshes lod = simplifyLevel(*from, count(rock), count(colluvium), level, -1.0, warnings);
    lod.bounds_min = meshes.bounds_min, lod.bounds_max = meshes.bounds_max;
    lod.durability_range = meshes.durability_range;
    lods.push_back(std::move(lod));
    from = &lods.back();
  }
  return lods;
}

}  // namespace rockbake
