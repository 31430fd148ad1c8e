#include "texture/dilate_texels.h"

#include <cstdint>

namespace rockbake {

void dilateTexels(TexelMap& map) {
  // Chessboard distance transform in two raster passes (forward, then backward), each texel
  // carrying the covered texel it is nearest to: exact for the 8-neighbour metric, 2 bytes a
  // texel besides the map, and serial, so ties always go the same way.
  const int size = map.size;
  const std::size_t n = map.texels.size();
  constexpr std::uint16_t kFar = 0xffff;
  std::vector<std::uint16_t> distance(n, kFar);
  bool any = false;
  for (std::size_t i = 0; i < n; ++i) {
    if (map.texels[i] & kDilatedTexel) map.texels[i] = kEmptyTexel;  // dilated before: again from scratch
    if (map.texels[i] != kEmptyTexel) distance[i] = 0, any = true;
  }
  if (!any) return;
  const auto origin = [&](std::size_t i) {
    return distance[i] == 0 ? std::uint32_t(i) : map.texels[i] & ~kDilatedTexel;
  };
  const auto relax = [&](std::size_t i, int nx, int ny) {
    if (nx < 0 || ny < 0 || nx >= size || ny >= size) return;
    const std::size_t j = std::size_t(ny) * std::size_t(size) + std::size_t(nx);
    if (distance[j] == kFar || distance[j] + 1 >= distance[i]) return;
    distance[i] = std::uint16_t(distance[j] + 1);
    map.texels[i] = kDilatedTexel | origin(j);
  };
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      const std::size_t i = std::size_t(y) * std::size_t(size) + std::size_t(x);
      relax(i, x - 1, y), relax(i, x - 1, y - 1), relax(i, x, y - 1), relax(i, x + 1, y - 1);
    }
  for (int y = size - 1; y >= 0; --y)
    for (int x = size - 1; x >= 0; --x) {
      const std::size_t i = std::size_t(y) * std::size_t(size) + std::size_t(x);
      relax(i, x + 1, y), relax(i, x + 1, y + 1), relax(i, x, y + 1), relax(i, x - 1, y + 1);
    }
}

}  // namespace rockbake
