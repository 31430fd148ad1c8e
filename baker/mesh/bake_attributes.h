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
//   history     when asked for and the rock has one, that of the nearest exposed rock voxel as
//               fractions of the run (SurfaceMesh::history): exposure age 1 − exp(−4 (N − exposed_at) / N),
//               scar freshness 1 − (N − scarred_at) / N (0 never scarred), burial covered_cycles /
//               (N + 1), for N the history's cycles (at least 1); the colluvium surface's is 0.
//               Otherwise left empty.
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
  bool history = false;                          // sample the rock's history (it has one: VoxelHistory)
};

AssetMeshes sampleAttributes(AssetMeshes meshes, const AttributeSources& sources);

struct PaletteParams {
  Palette palette = Palette::Natural;
  float durability_min = 0.0f, durability_max = 1.0f;  // range keyed to the palette's ends
  std::vector<PaletteLayer> layers;                    // natural: the preset's layers (sRGB), if any
  std::optional<SrgbColor> colluvium_color;            // natural: the preset's colluvium colour (sRGB)
  // natural: the look tints the colours where a mesh has one (SurfaceMesh::look); none: not.
  std::optional<LookParams> look;
  std::uint64_t seed = 0;  // the lichen's patches
  double voxel = 1.0;      // the grid's h, world units: the lichen patches' scale
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
//              blended towards the colluvium colour by coverage; then, with a look, tinted by it
//              (lookTint below)
AssetMeshes applyPalette(AssetMeshes meshes, const PaletteParams& params);

// The look's tint of a linear palette colour (docs/textures.md, "The look"): with the History RGBA
// `look` (age a, stain and varnish g, moisture m, dust d), the rockfall scar's freshness `scar`
// (SurfaceMesh::history) and `lichen` cover, each 0..1,
//   young faces paler     c · (1 + scars · (0.15 (1 − a)² + 0.3 scar))
//   stain and varnish     towards mix(stain colour, varnish colour, a) by 0.85 g
//   dust                  towards the dust colour by 0.8 d
//   lichen                towards the lichen colour by the cover
//   moisture              c · (1 − 0.35 m): wet rock is darker
// clamped to [0, 1]. `colours` holds the look's colours converted to linear once.
struct LookColours {
  std::array<float, 3> stain, varnish, dust, lichen;
};
LookColours lookColours(const LookParams& look);
std::array<float, 3> lookTint(std::array<float, 3> colour, const std::array<float, 4>& look, float scar, float lichen,
                              const LookParams& params, const LookColours& colours);

}  // namespace rockbake
