// Hits for every covered texel of a LOD (docs/textures.md): from the point of the LOD's
// surface at the texel's centre, along the LOD's interpolated normal, both ways within the
// cage, to the same surface of the bake source (rock to rock, colluvium to colluvium); the
// nearest hit either way wins (ray_source.h). Every map of the LOD is made from these hits,
// so the rays are cast once per LOD. TBB-parallel over rows; each texel's hit is a function of
// the texel alone, so the hits are the same at any thread count.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/surface_mesh.h"
#include "texture/rasterize_uv.h"
#include "texture/ray_source.h"

namespace rockbake {

inline constexpr std::uint32_t kNoHit = 0xffffffffu;

// 12 bytes a covered texel: the source triangle (of the texel's surface), its barycentrics
// u, v in 1/65535 steps, and the signed distance along the LOD's normal (world units).
struct TexelHit {
  std::uint32_t triangle = kNoHit;
  std::uint16_t u = 0, v = 0;
  float distance = 0;
};

struct TexelHits {
  std::vector<TexelHit> hits;          // one per covered texel, row-major
  std::vector<std::size_t> row_start;  // index in `hits` of each row's first covered texel; size + 1 entries
  // Per row, per block of kHitBlock texels: the row's covered texels before the block
  // (hitIndex finds any texel's hit without a scan of its row).
  std::vector<std::uint32_t> block_start;
  std::size_t missed = 0;  // covered texels whose rays found nothing within the cage
};

inline constexpr int kHitBlock = 64;

// The index in hits.hits of covered texel (x, y) of `texels`.
inline std::size_t hitIndex(const TexelMap& texels, const TexelHits& hits, int x, int y) {
  const std::size_t size = std::size_t(texels.size), blocks = (size + kHitBlock - 1) / kHitBlock;
  const int x0 = x / kHitBlock * kHitBlock;
  std::size_t k =
      hits.row_start[std::size_t(y)] + hits.block_start[std::size_t(y) * blocks + std::size_t(x / kHitBlock)];
  for (int i = x0; i < x; ++i) {
    const std::uint32_t t = texels.texels[std::size_t(y) * size + std::size_t(i)];
    k += t != kEmptyTexel && !(t & kDilatedTexel);
  }
  return k;
}

// Barycentric weights of texel (x, y)'s centre in `triangle` of `mesh` (by its uvs), clamped
// onto the triangle (a centre on its edge, snapped, may sit a hair outside).
std::array<double, 3> texelBarycentrics(const SurfaceMesh& mesh, std::uint32_t triangle, int x, int y, int size);

// `lod`: the meshes `texels` was rasterised from, with normals. `cage`: world units (> 0).
TexelHits traceTexels(const AssetMeshes& lod, const TexelMap& texels, const RaySource& source, double cage);

}  // namespace rockbake
