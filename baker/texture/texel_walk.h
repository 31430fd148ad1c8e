// The walk every map of bake_maps.h shares: each covered texel with its place on the LOD and
// its hit on the source, in parallel over rows, then the dilation into the empty texels.
#pragma once

#include <array>

#include <tbb/parallel_for.h>

#include "core/vec3.h"
#include "texture/bake_maps.h"
#include "texture/dilate_texels.h"

namespace rockbake::texture_detail {

// A point of a surface: its triangle's vertices and their weights.
struct SurfacePoint {
  const SurfaceMesh* mesh = nullptr;
  std::array<std::uint32_t, 3> vertex{};
  std::array<double, 3> weight{};

  template <class T>
  double scalar(const std::vector<T>& values) const {
    return weight[0] * values[vertex[0]] + weight[1] * values[vertex[1]] + weight[2] * values[vertex[2]];
  }
  template <class A>
  Vec3d vector(const std::vector<A>& values) const {
    Vec3d r{0, 0, 0};
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k)
        r[std::size_t(k)] += weight[std::size_t(i)] * values[vertex[std::size_t(i)]][std::size_t(k)];
    return r;
  }
};

struct TexelSample {
  int surface = 0;   // 0 rock, 1 colluvium
  SurfacePoint lod;  // the texel's centre on the LOD
  bool hit = false;
  SurfacePoint source;    // the hit on the source (when hit)
  float distance = 0.0f;  // signed, along the LOD's normal
};

// Calls write(texel index, sample) for every covered texel, then copies into every empty
// texel the `channels` values of the texel dilateTexels chose for it.
template <class T, class Write>
TextureImage<T> walkTexels(const LodBake& bake, int channels, Write&& write) {
  const TexelMap& texels = *bake.texels;
  const int size = texels.size;
  TextureImage<T> image{size, channels, std::vector<T>(std::size_t(size) * std::size_t(size) * std::size_t(channels))};
  tbb::parallel_for(0, size, [&](int y) {
    std::size_t k = bake.hits->row_start[std::size_t(y)];
    for (int x = 0; x < size; ++x) {
      const std::size_t i = std::size_t(y) * std::size_t(size) + std::size_t(x);
      const std::uint32_t t = texels.texels[i];
      if (t == kEmptyTexel || (t & kDilatedTexel)) continue;
      const TriangleRef ref = triangleRef(*bake.lod, t);
      TexelSample s;
      s.surface = ref.surface;
      s.lod.mesh = ref.surface == 0 ? &bake.lod->rock : &bake.lod->colluvium;
      s.lod.vertex = s.lod.mesh->triangles[ref.triangle];
      s.lod.weight = texelBarycentrics(*s.lod.mesh, ref.triangle, x, y, size);
      const TexelHit& h = bake.hits->hits[k++];
      if (h.triangle != kNoHit) {
        s.hit = true;
        s.source.mesh = ref.surface == 0 ? &bake.source->rock : &bake.source->colluvium;
        s.source.vertex = s.source.mesh->triangles[h.triangle];
        const double u = h.u / 65535.0, v = h.v / 65535.0;
        s.source.weight = {std::max(0.0, 1.0 - u - v), u, v};
        s.distance = h.distance;
      }
      write(i, s, &image.pixels[i * std::size_t(channels)]);
    }
  });
  fillEmptyTexels(texels, image.pixels, channels);
  return image;
}

}  // namespace rockbake::texture_detail
