// Levels of detail (docs/meshes.md): meshoptimizer edge-collapse simplification of
// each surface, borders locked, every kept vertex keeping its attributes and
// colour (meshoptimizer only removes vertices, so every vertex of a LOD lies on
// the surface it was simplified from); normals recomputed. LOD0 is simplified
// to an error bound, the further LODs to triangle budgets. No LOD has
// fold-overs or zero-area triangles (repairFoldOvers after the simplifier).
#pragma once

#include <cstddef>
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
// removed and the surface is cut apart where it glued two sheets together along
// an edge or at a vertex (splitNonManifold; the copies coincide). Should an
// edge still not be shared by exactly two faces, triangles around it are kept
// as they are and the rest simplified again; the best result is kept, and a
// warning logged if it still has such an edge.
std::vector<AssetMeshes> simplifyLods(const AssetMeshes& meshes, const LodParams& params);

// Makes a closed triangle mesh 2-manifold without moving anything: where
// several sheets meet along an edge (more than one face each way) or at a
// vertex, each sheet gets its own copies of the vertices there, with their
// attributes; normals are recomputed. Every edge must be used as often each
// way (as collapsing a closed mesh leaves it). Deterministic. Returns the
// vertices added.
std::size_t splitNonManifold(SurfaceMesh& mesh);

}  // namespace rockbake
