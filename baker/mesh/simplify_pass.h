// One simplification pass (docs/meshes.md, The repairs; simplify_lods.h
// runs the passes): meshoptimizer's edge collapse on the triangles not
// locked, their border with the locked ones held in place, then the
// simplifier's damage repaired as far as it can be.
//
// Takes a triangle mesh, its index buffer (three indices a triangle, the
// mesh's own), a lock flag per triangle, a target index count and
// meshoptimizer's relative error bound. After the simplifier: back-to-back
// pairs dropped (back_to_back.h), glued sheets cut apart (split_non_manifold.h),
// and, where every edge is then paired, fold-overs and zero-area triangles
// repaired (fold_over_repair.h). Gives the simplified mesh (vertices still
// used, in their order, copies last, every per-vertex array carried; normals
// recomputed) and what is left to lock around: torn edges, cuts and folds.
// Deterministic; logs its counts at debug level.
#pragma once

#include <cstddef>
#include <vector>

#include "core/surface_mesh.h"
#include "core/vec3.h"

namespace rockbake {

struct SimplifyPass {
  SurfaceMesh mesh;
  std::size_t bad_edges = 0;   // edges not shared by exactly two faces after the repair
  std::vector<Vec3f> torn;     // vertices of those edges
  std::vector<Vec3f> cut;      // pinches that cut the surface in two
  std::vector<Vec3f> folded;   // vertices of fold-overs and zero-area triangles the repair left
  std::size_t folds_left = 0;  // how many such triangles
};

// `level` (the LOD's number) is for the log only.
SimplifyPass simplifyPass(const SurfaceMesh& mesh, const std::vector<unsigned int>& indices,
                          const std::vector<char>& locked, std::size_t target_indices, float relative_error,
                          std::size_t level);

}  // namespace rockbake
