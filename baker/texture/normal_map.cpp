#include <cmath>
#include <stdexcept>

#include "texture/bake_maps.h"
#include "texture/texel_walk.h"

namespace rockbake {

using namespace texture_detail;
constexpr Vec3d kZero{0.0, 0.0, 0.0};  // normalised()'s fallback: a zero vector stays zero

TextureImage<std::uint16_t> bakeNormalMap(const LodBake& bake, bool directx) {
  for (const SurfaceMesh* m : {&bake.lod->rock, &bake.lod->colluvium})
    if (!m->triangles.empty() && m->tangents.size() != m->positions.size())
      throw std::invalid_argument("bakeNormalMap: the " + m->name + " LOD has no tangent frames");
  return walkTexels<std::uint16_t>(bake, 3, [&](std::size_t, const TexelSample& s, std::uint16_t* out) {
    Vec3d c{0, 0, 1};  // the LOD's own normal where the rays missed
    if (s.hit) {
      // The frame a glTF client interpolates: tangent, bitangent = cross(N, T) · w, normal.
      const SurfaceMesh& m = *s.lod.mesh;
      Vec3d t{0, 0, 0}, b{0, 0, 0}, n{0, 0, 0};
      for (int i = 0; i < 3; ++i) {
        const auto& tw = m.tangents[s.lod.vertex[std::size_t(i)]];
        const Vec3d vt{tw[0], tw[1], tw[2]}, vn = toVec3d(m.normals[s.lod.vertex[std::size_t(i)]]);
        const double w = s.lod.weight[std::size_t(i)];
        t = add(t, scale(vt, w));
        b = add(b, scale(cross(vn, vt), w * tw[3]));
        n = add(n, scale(vn, w));
      }
      t = normalised(t, kZero), b = normalised(b, kZero), n = normalised(n, kZero);
      const Vec3d target = normalised(s.source.vector(s.source.mesh->normals), kZero);
      // [t b n] c = target: c = the inverse frame applied to the target (rows b×n, n×t, t×b over det).
      const double det = dot(t, cross(b, n));
      if (std::abs(det) > 1e-6 && length(target) > 0) {
        const Vec3d solved = normalised(
            Vec3d{dot(cross(b, n), target) / det, dot(cross(n, t), target) / det, dot(cross(t, b), target) / det},
            kZero);
        if (std::isfinite(solved[0]) && length(solved) > 0) c = solved;
      }
    }
    if (directx) c[1] = -c[1];  // the bitangent points down the texture
    for (int k = 0; k < 3; ++k)
      out[k] = std::uint16_t(std::lround(std::clamp((c[std::size_t(k)] + 1.0) * 0.5, 0.0, 1.0) * 65535.0));
  });
}

}  // namespace rockbake
