#include "texture/trace_texels.h"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>

#include "core/vec3.h"

namespace rockbake {

constexpr Vec3d kZero{0.0, 0.0, 0.0};  // normalised()'s fallback: a zero vector stays zero

std::array<double, 3> texelBarycentrics(const SurfaceMesh& mesh, std::uint32_t triangle, int x, int y, int size) {
  const auto& t = mesh.triangles[triangle];
  const double px = (x + 0.5) / size, py = (y + 0.5) / size;
  const auto& a = mesh.uvs[t[0]];
  const auto& b = mesh.uvs[t[1]];
  const auto& c = mesh.uvs[t[2]];
  const double area = (double(b[0]) - a[0]) * (double(c[1]) - a[1]) - (double(b[1]) - a[1]) * (double(c[0]) - a[0]);
  if (area == 0) return {1.0 / 3, 1.0 / 3, 1.0 / 3};
  const double w1 = ((px - a[0]) * (double(c[1]) - a[1]) - (py - a[1]) * (double(c[0]) - a[0])) / area;
  const double w2 = ((double(b[0]) - a[0]) * (py - a[1]) - (double(b[1]) - a[1]) * (px - a[0])) / area;
  std::array<double, 3> w{1.0 - w1 - w2, w1, w2};
  double sum = 0;
  for (double& v : w) sum += (v = std::max(v, 0.0));
  for (double& v : w) v /= sum;
  return w;
}

TexelHits traceTexels(const AssetMeshes& lod, const TexelMap& texels, const RaySource& source, double cage) {
  const int size = texels.size;
  TexelHits out;
  out.row_start.assign(std::size_t(size) + 1, 0);
  const std::size_t blocks = (std::size_t(size) + kHitBlock - 1) / kHitBlock;
  out.block_start.assign(std::size_t(size) * blocks, 0);
  for (int y = 0; y < size; ++y) {
    std::size_t covered = 0;
    for (int x = 0; x < size; ++x) {
      if (x % kHitBlock == 0)
        out.block_start[std::size_t(y) * blocks + std::size_t(x / kHitBlock)] = std::uint32_t(covered);
      const std::uint32_t t = texels.texels[std::size_t(y) * std::size_t(size) + std::size_t(x)];
      covered += t != kEmptyTexel && !(t & kDilatedTexel);
    }
    out.row_start[std::size_t(y) + 1] = out.row_start[std::size_t(y)] + covered;
  }
  out.hits.resize(out.row_start.back());
  std::vector<std::size_t> missed(std::size_t(size), 0);
  // Each row's covered texels in packets of RaySource::kPacket, neighbours traced together.
  tbb::parallel_for(0, size, [&](int y) {
    constexpr int kPacket = RaySource::kPacket;
    int surface[kPacket];
    std::array<float, 3> origin[kPacket], direction[kPacket];
    SourceHit found[kPacket];
    std::size_t k = out.row_start[std::size_t(y)];
    int lanes = 0;
    const auto flush = [&] {
      source.nearestAlong(lanes, surface, origin, direction, float(cage), found);
      for (int i = 0; i < lanes; ++i) {
        TexelHit& h = out.hits[k++];
        if (!found[i].hit) {
          ++missed[std::size_t(y)];
          continue;
        }
        h.triangle = found[i].triangle;
        h.u = std::uint16_t(std::lround(std::clamp(found[i].u, 0.0f, 1.0f) * 65535.0f));
        h.v = std::uint16_t(std::lround(std::clamp(found[i].v, 0.0f, 1.0f) * 65535.0f));
        h.distance = found[i].distance;
      }
      lanes = 0;
    };
    for (int x = 0; x < size; ++x) {
      const std::uint32_t t = texels.texels[std::size_t(y) * std::size_t(size) + std::size_t(x)];
      if (t == kEmptyTexel || (t & kDilatedTexel)) continue;
      const TriangleRef ref = triangleRef(lod, t);
      const SurfaceMesh& m = ref.surface == 0 ? lod.rock : lod.colluvium;
      const auto w = texelBarycentrics(m, ref.triangle, x, y, size);
      const auto& tri = m.triangles[ref.triangle];
      Vec3d p{0, 0, 0}, n{0, 0, 0};
      for (int i = 0; i < 3; ++i) {
        p = add(p, scale(toVec3d(m.positions[tri[i]]), w[i]));
        n = add(n, scale(toVec3d(m.normals[tri[i]]), w[i]));
      }
      n = normalised(n, kZero);
      surface[lanes] = ref.surface;
      origin[lanes] = {float(p[0]), float(p[1]), float(p[2])};
      direction[lanes] = {float(n[0]), float(n[1]), float(n[2])};
      if (++lanes == kPacket) flush();
    }
    if (lanes > 0) flush();
  });
  for (std::size_t m : missed) out.missed += m;
  return out;
}

}  // namespace rockbake
