// Surface detail (docs/meshes.md, `mesh.detail`): seeded roughness below the voxel
// scale, displaced along the refined surface's normals before simplification.
//
// Each rock vertex moves by
//   amplitude · weight(v) · n(p / period) / rms(n)
// where n is `octaves` of improved Perlin noise seeded from (seed, "mesh-detail"),
// rms(n) its root mean square over the mesh's vertices (so a neutral weight of 1
// gives a displacement whose RMS is `amplitude`), and
//   weight(v) = (½ + softness) · (½ + s) · (1 − colluvium coverage)
// with softness = (D_max − D) / (D_max − D_min) over the preset's durability
// range (½ when the range is empty) and s the calibrated exposure (½ flat): soft,
// exposed rock is roughest. Vertices on the ground cap (z = 0 with ground) do
// not move, and no vertex is pushed below z = 0. Where the displacement would
// fold the surface (a triangle turned over or against a neighbour, or
// collapsed), it is halved at that triangle's corners, repeatedly, and dropped
// there if that is not enough: a clean input stays free of fold-overs. The
// result is a pure function of the mesh and the parameters (byte-identical at
// any thread count).
#pragma once

#include <cstdint>

#include "core/surface_mesh.h"
#include "preset/preset.h"

namespace rockbake {

struct DetailParams {
  NoiseParams noise;  // amplitude and period in world units, octaves 1..8; amplitude 0: no-op
  std::uint64_t seed = 0;
  float durability_min = 0.0f, durability_max = 1.0f;  // the preset's range over the rock voxels
  bool ground = true;                                  // z = 0 is the ground cap
};

// Displaces `mesh` (triangles only, with normals and attributes) in place and
// recomputes its normals. An empty mesh or amplitude 0 leaves it unchanged.
void displaceSurface(SurfaceMesh& mesh, const DetailParams& params);

}  // namespace rockbake
