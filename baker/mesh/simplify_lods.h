// Levels of detail (SPEC §3): meshoptimizer edge-collapse simplification of
// each surface, borders locked, every kept vertex keeping its attributes and
// colour (meshoptimizer only removes vertices, so every vertex of a LOD lies on
// the surface it was simplified from); normals recomputed. LOD0 is simplified
// to an error bound, the further LODs to triangle budgets. No LOD has
// fold-overs or zero-area triangles (repairFoldOvers after the simplifier).
#pragma once

#include <vector>

#include "core/surface_mesh.h"

namespace rockbake {

struct LodParams {
  // Each entry either a ratio in (0, 1) (target triangles ÷ the input's) or a
  // triangle count >= 1 for both surfaces together, shared between them in
  // proportion to the input's triangles.
  std::vector<double> targets;
};

// LOD0: each surface simplified as far as meshoptimizer can while its error
// (its distance estimate from the input surface) stays within `max_error`
// (world units). Input meshes must be triangle-only.
AssetMeshes simplifyToError(const AssetMeshes& meshes, double max_error);

// One AssetMeshes per target, in order. Input meshes must be triangle-only.
// Targets are approached with no error bound (meshoptimizer may stop a little
// short where every collapse would flip a face). meshoptimizer does not keep
// manifoldness by itself, so coincident back-to-back triangle pairs are
// removed and vertices where it pinched two sheets together are split (the
// copies coincide). If an edge still is not shared by exactly two faces (sheets
// pinched in a way the repair cannot pair), the surface is simplified once more
// to a target 1 % lower; should that fail too, the better result is kept and a
// warning logged (seen: a few edges in a million triangles on some assets).
std::vector<AssetMeshes> simplifyLods(const AssetMeshes& meshes, const LodParams& params);

}  // namespace rockbake
