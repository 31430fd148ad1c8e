#include "texture/ambient_occlusion.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include <tbb/parallel_for.h>

#include "core/hash.h"
#include "core/vec3.h"

namespace rockbake {

constexpr Vec3d kZero{0.0, 0.0, 0.0};  // normalised()'s fallback: a zero vector stays zero

namespace {

double radicalInverse(std::uint32_t i) {
  i = (i << 16) | (i >> 16);
  i = ((i & 0x00ff00ffu) << 8) | ((i & 0xff00ff00u) >> 8);
  i = ((i & 0x0f0f0f0fu) << 4) | ((i & 0xf0f0f0f0u) >> 4);
  i = ((i & 0x33333333u) << 2) | ((i & 0xccccccccu) >> 2);
  i = ((i & 0x55555555u) << 1) | ((i & 0xaaaaaaaau) >> 1);
  return double(i) * 0x1.0p-32;
}

}  // namespace

std::array<std::vector<float>, 2> vertexOcclusion(const AssetMeshes& at, const RaySource& source,
                                                  const TextureParams& params, std::uint64_t seed) {
  checkTextureParams(params);
  const double pi = 3.14159265358979323846;
  const int count = params.ao_rays;
  const float reach = params.ao_distance > 0 ? float(params.ao_distance) : std::numeric_limits<float>::infinity();
  // A ray starts this far along, clear of the triangles around its own vertex.
  const float start = float(1e-4 * source.radius());
  const std::uint64_t purpose = purposeId("texture-occlusion");
  std::array<std::vector<float>, 2> open;
  const SurfaceMesh* surfaces[2] = {&at.rock, &at.colluvium};
  for (int s = 0; s < 2; ++s) {
    const SurfaceMesh& m = *surfaces[s];
    open[s].assign(m.positions.size(), 1.0f);
    if (m.triangles.empty()) continue;
    tbb::parallel_for(std::size_t(0), m.positions.size(), [&](std::size_t v) {
      const Vec3d n = normalised(toVec3d(m.normals[v]), kZero);
      // An orthonormal frame about the normal (Duff et al., "Building an Orthonormal Basis, Revisited", 2017).
      const double sign = std::copysign(1.0, n[2]);
      const double a = -1.0 / (sign + n[2]), b = n[0] * n[1] * a;
      const Vec3d t1{1.0 + sign * n[0] * n[0] * a, sign * b, -sign * n[0]}, t2{b, sign + n[1] * n[1] * a, -n[1]};
      const auto& p = m.positions[v];
      std::uint32_t bits[3];
      std::memcpy(bits, p.data(), sizeof bits);
      const std::uint64_t h =
          counterHash(seed, purpose, std::uint64_t(s), mix64(std::uint64_t(bits[0]) << 32 | bits[1]) ^ bits[2]);
      const double shift1 = unitInterval(h), shift2 = unitInterval(mix64(h));
      int hits = 0;
      std::array<float, 3> packet[RaySource::kPacket];
      for (int first = 0; first < count; first += RaySource::kPacket) {
        const int lanes = std::min(RaySource::kPacket, count - first);
        for (int j = 0; j < lanes; ++j) {
          const int i = first + j;
          const double u1 = std::fmod((i + 0.5) / count + shift1, 1.0);
          const double u2 = std::fmod(radicalInverse(std::uint32_t(i)) + shift2, 1.0);
          const double r = std::sqrt(u1), phi = 2 * pi * u2;
          const Vec3d d =
              add(add(scale(t1, r * std::cos(phi)), scale(t2, r * std::sin(phi))), scale(n, std::sqrt(1.0 - u1)));
          packet[j] = {float(d[0]), float(d[1]), float(d[2])};
        }
        hits += source.occludedCount(p, lanes, packet, start, reach);
      }
      open[s][v] = 1.0f - float(hits) / float(count);
    });
  }
  return open;
}

}  // namespace rockbake
