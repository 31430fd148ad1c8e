#include "texture/mesh_helpers.h"

#include <algorithm>
#include <utility>

namespace rockbake::texture_detail {

std::vector<std::array<std::uint32_t, 3>> triangleNeighbours(
    const std::vector<std::array<std::uint32_t, 3>>& triangles) {
  const std::size_t nt = triangles.size();
  std::vector<std::array<std::uint32_t, 3>> across(nt, {kNoTriangle, kNoTriangle, kNoTriangle});
  // Every half-edge keyed by its unordered vertex pair; sorting brings each edge's uses together.
  struct HalfEdge {
    std::uint64_t key;
    std::uint32_t corner;  // 3 · triangle + k
    bool forward;          // traversed from the lower vertex index to the higher
  };
  std::vector<HalfEdge> half(3 * nt);
  for (std::size_t t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = triangles[t][k], b = triangles[t][(k + 1) % 3];
      half[3 * t + k] = {std::uint64_t(std::min(a, b)) << 32 | std::max(a, b), std::uint32_t(3 * t + k), a < b};
    }
  std::sort(half.begin(), half.end(),
            [](const HalfEdge& x, const HalfEdge& y) { return x.key != y.key ? x.key < y.key : x.corner < y.corner; });
  for (std::size_t i = 0; i < half.size();) {
    std::size_t j = i + 1;
    while (j < half.size() && half[j].key == half[i].key) ++j;
    if (j - i == 2 && half[i].forward != half[i + 1].forward && (half[i].key >> 32) != (half[i].key & 0xffffffffu)) {
      const std::uint32_t c0 = half[i].corner, c1 = half[i + 1].corner;
      across[c0 / 3][c0 % 3] = c1 / 3;
      across[c1 / 3][c1 % 3] = c0 / 3;
    }
    i = j;
  }
  return across;
}

}  // namespace rockbake::texture_detail
