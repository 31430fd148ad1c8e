// Levels of detail (docs/meshes.md, LOD0 and its bound; The LOD chain and
// its budgets). Each surface is simplified by meshoptimizer's edge collapse
// in passes (simplify_pass.h), borders locked; meshoptimizer only removes
// vertices, so every vertex of a LOD lies on the surface it was simplified
// from and keeps its values in every per-vertex array; normals recomputed.
// LOD0 is simplified to an error bound, the further LODs to triangle budgets.
//
// meshoptimizer does not keep manifoldness by itself: each pass cuts glued
// sheets apart and repairs fold-overs (simplify_pass.h). Where a collapse
// still tore an edge, cut the surface in two or (LOD0) left a fold, the
// triangles around that place are locked and the rest simplified again; the
// cleanest pass is kept, and a warning logged naming the LOD if it still has
// such an edge or fold. A budgeted LOD has no error bound to keep: what the
// repair leaves is relaxed (relax_fold_overs.h) and collapsed specks dropped
// (collapsed_specks.h). Input meshes must be triangle-only. Deterministic; the
// two surfaces simplify in parallel.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "core/surface_mesh.h"

namespace rockbake {

struct LodParams {
  // Each entry either a ratio in (0, 1) (target triangles ÷ the input's) or a
  // triangle count >= 1 for both surfaces together, shared between them in
  // proportion to the input's triangles.
  std::vector<double> targets;
};

// What a simplification could not repair, one line each, in LOD and surface
// order ("LOD1 of the rock surface keeps 2 folded or zero-area triangles"). A
// caller that passes none gets them logged as warnings; one that passes a list
// says whose asset they are when it logs them.
using SimplifyWarnings = std::vector<std::string>;

// LOD0: each surface simplified as far as meshoptimizer can while its error
// (its distance estimate from the input surface) stays within `max_error`
// (world units).
AssetMeshes simplifyToError(const AssetMeshes& meshes, double max_error, SimplifyWarnings* warnings = nullptr);

// One AssetMeshes per target, in order. Targets are approached with no error
// bound (meshoptimizer may stop a little short where every collapse would flip
// a face).
std::vector<AssetMeshes> simplifyLods(const AssetMeshes& meshes, const LodParams& params,
                                      SimplifyWarnings* warnings = nullptr);

}  // namespace rockbake
