// The rock's look in the maps (docs/textures.md): what render_templates/studio.pov made inside
// POV-Ray (colour varied within each layer at two scales, granular colluvium), moved into
// the base colour and roughness so every engine gets it. Each term multiplies the palette's
// colour by 1 + a · n(p / scale) with n seeded improved Perlin noise of mean zero, so each
// layer keeps its mean colour:
//   rock       mottling     a = 0.10 at 0.25 × the asset's radius (the template's granite turbulence)
//              variation    a = 0.06 at the voxel size (per-voxel variation)
//              grain        a = 0.05 at 0.02 × the radius
//   colluvium  grains       a = 0.12 at 0.015 × the radius, and the variation
// blended by colluvium coverage. Roughness: rock 0.9 (soft) … 0.75 (most durable) ± 0.04 by
// the grain, colluvium 0.95. Positions are the bake source's, world units, so every LOD reads
// the same pattern.
#pragma once

#include <array>
#include <cstdint>

#include "core/perlin_noise.h"

namespace rockbake {

class RockLook {
 public:
  // `radius`: half the asset's bounding-box diagonal; `voxel_size`: the grid's h (0: no
  // per-voxel term); `durability_range`: what durability normalises by (AssetMeshes).
  // `varied` false: no noise at all, the palette's colours exactly and the roughness without
  // grain (the debug and curvature palettes, whose colours are data).
  RockLook(std::uint64_t seed, double radius, double voxel_size, std::array<float, 2> durability_range,
           bool varied = true);

  // The factor on the palette's linear colour at `p`, with colluvium coverage `cover` (0..1).
  float colourFactor(const std::array<double, 3>& p, float cover) const;
  // Roughness 0..1 at `p` with durability `durability` (0 off rock) and coverage `cover`.
  float roughness(const std::array<double, 3>& p, float durability, float cover) const;
  // Durability normalised over the range as COLOR_1 does: 0 where durability <= 0.
  float normalisedDurability(float durability) const;

 private:
  PerlinNoise mottle_, variation_, grain_, colluvium_grain_;
  double mottle_scale_, variation_scale_, grain_scale_, colluvium_scale_;
  bool varied_;
  float durability_min_, durability_span_;
};

// Roughness where the surface has a look (mesh/surface_look.h; RGBA age, stain and varnish,
// moisture, dust): varnish is smoother (towards 0.55 by half the stain), wet rock smoother still
// (towards 0.35 by 0.6 of the moisture), dust rough (towards 0.97 by the dust).
float weatheredRoughness(float roughness, const std::array<double, 4>& look);

}  // namespace rockbake
