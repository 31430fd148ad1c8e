// Dilation (docs/textures.md): every map is filled into its gutters and the empty atlas, so
// that bilinear filtering at a chart's edge and the mip levels a renderer builds read the
// chart's own values instead of black. dilateTexels points each empty texel of a TexelMap at
// the covered texel nearest to it (chessboard distance, two raster passes; ties go to the
// texel found first), once per atlas; fillEmptyTexels then copies that texel's value in
// every map.
#pragma once

#include <cstddef>
#include <vector>

#include "texture/rasterize_uv.h"

namespace rockbake {

// Empty texels become kDilatedTexel | the index of the covered texel they copy. Without any
// covered texel the map is left as it is. Deterministic.
void dilateTexels(TexelMap& map);

// The covered texel an empty texel copies, or the texel itself when it is covered.
inline std::size_t valueTexel(const TexelMap& map, std::size_t texel) {
  const std::uint32_t t = map.texels[texel];
  return t != kEmptyTexel && (t & kDilatedTexel) ? std::size_t(t & ~kDilatedTexel) : texel;
}

// Copies, into each empty texel of `pixels` (`channels` values per texel, row-major, the
// map's size), the values of the texel dilateTexels chose for it.
template <class T>
void fillEmptyTexels(const TexelMap& map, std::vector<T>& pixels, int channels) {
  const std::size_t n = map.texels.size(), c = std::size_t(channels);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t from = valueTexel(map, i);
    if (from != i)
      for (std::size_t k = 0; k < c; ++k) pixels[i * c + k] = pixels[from * c + k];
  }
}

}  // namespace rockbake
