// Levels of detail (SPEC §3): meshoptimizer edge-collapse simplification of
// each surface to a share of its triangles, borders locked, every kept vertex
// keeping its attributes and colour; normals recomputed.
#pragma once

#include <vector>

#include "core/surface_mesh.h"

namespace rockbake {

struct LodParams {
  std::vector<double> ratios;  // each in (0, 1): target triangles ÷ input triangles
};

// One AssetMeshes per ratio, in order. Input meshes must be triangle-only.
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
