// Baked per-vertex attributes and palettes (docs/meshes.md).
//
// sampleAttributes reads the final grid at each vertex (before subdivision, so
// OpenSubdiv refines the values alongside the positions):
//   durability  D of the nearest rock voxel (0 on the colluvium surface)
//   colluvium   rock surface: the share of colluvium among the non-rock voxels
//               of the 3×3×3 block around the vertex, 0..1; colluvium surface: 1
//   curvature   calibrated exposure s (docs/model.md §3) of the nearest exposed rock
//               voxel, 0..1, ½ flat; ½ on the colluvium surface
//   altitude    normalised, 0 at the ground, 1 at the top of grid.size
// applyPalette turns them into linear RGB colours in [0, 1].
#pragma once

#include <optional>
#include <vector>

#include "core/surface_mesh.h"
#include "core/voxel_rock.h"
#include "preset/preset.h"

namespace rockbake {

struct AttributeSources {
  const VoxelRock* rock = nullptr;               // the final grid
  const std::vector<float>* exposure = nullptr;  // exposureField(rock, preset): s per voxel, 0 off exposed rock
};

AssetMeshes sampleAttributes(AssetMeshes meshes, const AttributeSources& sources);

struct PaletteParams {
  Palette palette = Palette::Natural;
  float durability_min = 0.0f, durability_max = 1.0f;  // range keyed to the palette's ends
  std::vector<PaletteLayer> layers;                    // natural: the preset's layers (sRGB), if any
  std::optional<SrgbColor> colluvium_color;            // natural: the preset's colluvium colour (sRGB)
};

// The preset's palette with the durability range over the rock voxels of
// `rock` ([0, 1] if there are none).
PaletteParams paletteParams(const VoxelRock& rock, const VertexPaletteParams& bake);

// Fills `colors` (linear RGB) of both surfaces from their attributes:
//   debug      blue (soft) → cyan → green → yellow → red (durable); purple by colluvium coverage
//   curvature  blue (concave, s = 0) → light grey (flat, s = ½) → red (convex, s = 1)
//   natural    the preset's layers (bake.layers: colours at durabilities,
//              interpolated in linear light), or by default sandstone keyed to
//              the durability range, pale buff (soft) → deep red-brown (durable);
//              blended towards the colluvium colour by coverage
AssetMeshes applyPalette(AssetMeshes meshes, const PaletteParams& params);

}  // namespace rockbake
