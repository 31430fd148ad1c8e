// The walk every map of bake_maps.h shares: each covered texel with its place on the LOD and
// its hit on the source, in parallel over rows, then the dilation into the empty texels.
#pragma once

#include <algorithm>
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

// The interpolated value of a per-vertex array of four (SurfaceMesh::look).
template <class A>
std::array<double, 4> quadAt(const SurfacePoint& at, const std::vector<A>& values) {
  std::array<double, 4> r{0, 0, 0, 0};
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t k = 0; k < 4; ++k) r[k] += at.weight[i] * values[at.vertex[i]][k];
  return r;
}

struct TexelSample {
  int surface = 0;   // 0 rock, 1 colluvium
  SurfacePoint lod;  // the texel's centre on the LOD
  bool hit = false;
  SurfacePoint source;    // the hit on the source (when hit)
  float distance = 0.0f;  // signed, along the LOD's normal
};

// The sample of covered texel (x, y) of the LOD (texel map entry `t`), with its hit.
inline TexelSample texelSample(const LodBake& bake, int x, int y, std::uint32_t t, const TexelHit& h) {
  const TriangleRef ref = triangleRef(*bake.lod, t);
  TexelSample s;
  s.surface = ref.surface;
  s.lod.mesh = ref.surface == 0 ? &bake.lod->rock : &bake.lod->colluvium;
  s.lod.vertex = s.lod.mesh->triangles[ref.triangle];
  s.lod.weight = texelBarycentrics(*s.lod.mesh, ref.triangle, x, y, bake.texels->size);
  if (h.triangle != kNoHit) {
    s.hit = true;
    s.source.mesh = ref.surface == 0 ? &bake.source->rock : &bake.source->colluvium;
    s.source.vertex = s.source.mesh->triangles[h.triangle];
    const double u = h.u / 65535.0, v = h.v / 65535.0;
    s.source.weight = {std::max(0.0, 1.0 - u - v), u, v};
    s.distance = h.distance;
  }
  return s;
}

// Calls write(texel index, sample, its values) for every covered texel, then copies into every
// empty texel the `channels` values of the texel dilateTexels chose for it. With a band
// (bake.first_row, bake.last_row) only its rows are made, image.first_row says which: an
// empty texel there gets its values by writing the chosen texel's sample again (it may lie in
// any row; one in the band is copied), the same values as the whole map's copy.
template <class T, class Write>
TextureImage<T> walkTexels(const LodBake& bake, int channels, Write&& write) {
  const TexelMap& texels = *bake.texels;
  const int size = texels.size;
  const int first = std::clamp(bake.first_row, 0, size);
  const int last = bake.last_row < 0 ? size : std::clamp(bake.last_row, first, size);
  const bool whole = first == 0 && last == size;
  const std::size_t c = std::size_t(channels);
  const std::size_t offset = std::size_t(first) * std::size_t(size);  // the band's first texel
  TextureImage<T> image{size, channels, std::vector<T>(std::size_t(last - first) * std::size_t(size) * c), first};
  tbb::parallel_for(first, last, [&](int y) {
    std::size_t k = bake.hits->row_start[std::size_t(y)];
    for (int x = 0; x < size; ++x) {
      const std::size_t i = std::size_t(y) * std::size_t(size) + std::size_t(x);
      const std::uint32_t t = texels.texels[i];
      if (t == kEmptyTexel || (t & kDilatedTexel)) continue;
      write(i, texelSample(bake, x, y, t, bake.hits->hits[k++]), &image.pixels[(i - offset) * c]);
    }
  });
  if (!whole)  // an empty texel copies a covered texel of the band, or makes the values of one outside it
    tbb::parallel_for(first, last, [&](int y) {
      for (int x = 0; x < size; ++x) {
        const std::size_t i = std::size_t(y) * std::size_t(size) + std::size_t(x);
        const std::uint32_t t = texels.texels[i];
        if (t == kEmptyTexel || !(t & kDilatedTexel)) continue;
        const std::size_t j = t & ~kDilatedTexel;
        T* out = &image.pixels[(i - offset) * c];
        if (j >= offset && j < std::size_t(last) * std::size_t(size)) {
          std::copy_n(&image.pixels[(j - offset) * c], c, out);
          continue;
        }
        const int jx = int(j % std::size_t(size)), jy = int(j / std::size_t(size));
        const TexelHit& h = bake.hits->hits[hitIndex(texels, *bake.hits, jx, jy)];
        write(j, texelSample(bake, jx, jy, texels.texels[j], h), out);
      }
    });
  if (whole) fillEmptyTexels(texels, image.pixels, channels);
  return image;
}

}  // namespace rockbake::texture_detail
