#include "texture/rasterize_uv.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <tbb/parallel_for.h>

namespace rockbake {
namespace {

constexpr int kSubTexel = 256;  // fixed-point steps per texel
constexpr int kBandRows = 32;

struct FixedTriangle {
  std::int64_t x[3], y[3];  // in 1/kSubTexel texel, positively oriented
  std::uint32_t index;
};

// The top-left rule: an edge keeps the centres lying on it when it runs this way; the same
// edge run the other way (the neighbour's) does not.
bool ownsEdge(std::int64_t dx, std::int64_t dy) {
  return dy > 0 || (dy == 0 && dx < 0);
}

void rasterizeTriangle(const FixedTriangle& t, int size, int row0, int row1, std::vector<std::uint32_t>& texels,
                       std::vector<std::uint8_t>& contested) {
  const std::int64_t lo_x = std::min({t.x[0], t.x[1], t.x[2]}), hi_x = std::max({t.x[0], t.x[1], t.x[2]});
  const std::int64_t lo_y = std::min({t.y[0], t.y[1], t.y[2]}), hi_y = std::max({t.y[0], t.y[1], t.y[2]});
  // Texels whose centre (x · S + S/2) lies in [lo, hi].
  const auto first = [](std::int64_t lo) { return int((lo - kSubTexel / 2 + kSubTexel - 1) / kSubTexel); };
  const auto last = [](std::int64_t hi) { return int(std::floor(double(hi - kSubTexel / 2) / kSubTexel)); };
  const int x0 = std::max(0, first(std::max<std::int64_t>(lo_x, 0))), x1 = std::min(size - 1, last(hi_x));
  const int y0 = std::max(row0, first(std::max<std::int64_t>(lo_y, 0))), y1 = std::min(row1 - 1, last(hi_y));
  for (int y = y0; y <= y1; ++y) {
    const std::int64_t py = std::int64_t(y) * kSubTexel + kSubTexel / 2;
    for (int x = x0; x <= x1; ++x) {
      const std::int64_t px = std::int64_t(x) * kSubTexel + kSubTexel / 2;
      bool inside = true;
      for (int k = 0; k < 3 && inside; ++k) {
        const int j = (k + 1) % 3;
        const std::int64_t dx = t.x[j] - t.x[k], dy = t.y[j] - t.y[k];
        const std::int64_t e = dx * (py - t.y[k]) - dy * (px - t.x[k]);
        inside = e > 0 || (e == 0 && ownsEdge(dx, dy));
      }
      if (!inside) continue;
      const std::size_t i = std::size_t(y) * std::size_t(size) + std::size_t(x);
      if (texels[i] == kEmptyTexel)
        texels[i] = t.index;
      else
        contested[std::size_t(y - row0) * std::size_t(size) + std::size_t(x)] = 1;
    }
  }
}

}  // namespace

TexelMap rasterizeUv(const AssetMeshes& meshes, int size) {
  if (size < 1 || size > 8192) throw std::invalid_argument("rasterizeUv: size outside 1..8192");
  TexelMap map;
  map.size = size;
  map.texels.assign(std::size_t(size) * std::size_t(size), kEmptyTexel);
  const int bands = (size + kBandRows - 1) / kBandRows;
  std::vector<std::vector<FixedTriangle>> binned(static_cast<std::size_t>(bands));
  std::uint32_t index = 0;
  for (const SurfaceMesh* mesh : {&meshes.rock, &meshes.colluvium}) {
    if (mesh->triangles.empty()) continue;
    if (mesh->uvs.size() != mesh->positions.size())
      throw std::invalid_argument("rasterizeUv: the " + mesh->name + " surface has no uv per vertex");
    for (const auto& tri : mesh->triangles) {
      FixedTriangle t;
      t.index = index++;
      for (int k = 0; k < 3; ++k) {
        const auto& uv = mesh->uvs[tri[k]];
        t.x[k] = std::llround(double(uv[0]) * size * kSubTexel);
        t.y[k] = std::llround(double(uv[1]) * size * kSubTexel);
      }
      const std::int64_t area2 = (t.x[1] - t.x[0]) * (t.y[2] - t.y[0]) - (t.y[1] - t.y[0]) * (t.x[2] - t.x[0]);
      if (area2 == 0) continue;  // covers no centre
      if (area2 < 0) std::swap(t.x[1], t.x[2]), std::swap(t.y[1], t.y[2]);
      const std::int64_t lo = std::min({t.y[0], t.y[1], t.y[2]}), hi = std::max({t.y[0], t.y[1], t.y[2]});
      const int b0 = std::clamp(int(lo / (kSubTexel * kBandRows)), 0, bands - 1);
      const int b1 = std::clamp(int(hi / (kSubTexel * kBandRows)), 0, bands - 1);
      for (int b = b0; b <= b1; ++b) binned[std::size_t(b)].push_back(t);
    }
  }
  std::vector<std::size_t> contested(std::size_t(bands), 0);
  tbb::parallel_for(0, bands, [&](int b) {
    const int row0 = b * kBandRows, row1 = std::min(size, row0 + kBandRows);
    std::vector<std::uint8_t> marks(std::size_t(row1 - row0) * std::size_t(size), 0);
    for (const FixedTriangle& t : binned[std::size_t(b)]) rasterizeTriangle(t, size, row0, row1, map.texels, marks);
    contested[std::size_t(b)] = std::size_t(std::count(marks.begin(), marks.end(), std::uint8_t(1)));
  });
  for (std::size_t c : contested) map.contested += c;
  map.covered = std::size_t(
      std::count_if(map.texels.begin(), map.texels.end(), [](std::uint32_t t) { return t != kEmptyTexel; }));
  return map;
}

}  // namespace rockbake
