#include <algorithm>
#include <cmath>

#include "texture/bake_maps.h"
#include "texture/texel_walk.h"

namespace rockbake {

using namespace texture_detail;

TextureImage<std::uint8_t> bakeOrm(const LodBake& bake, const std::array<std::vector<float>, 2>& occlusion,
                                   const RockLook& look) {
  const auto byte = [](double v) { return std::uint8_t(std::lround(std::clamp(v, 0.0, 1.0) * 255.0)); };
  return walkTexels<std::uint8_t>(bake, 3, [&](std::size_t, const TexelSample& s, std::uint8_t* out) {
    const SurfacePoint& at = s.hit ? s.source : s.lod;
    const SurfaceMesh& m = *at.mesh;
    const bool attributes = m.durability.size() == m.positions.size() && m.colluvium.size() == m.positions.size();
    const float cover = s.surface == 1 ? 1.0f : attributes ? float(at.scalar(m.colluvium)) : 0.0f;
    const float durability = attributes ? float(at.scalar(m.durability)) : 0.0f;
    const std::vector<float>& open = occlusion[std::size_t(s.surface)];
    out[0] = byte(open.size() == s.lod.mesh->positions.size() ? s.lod.scalar(open) : 1.0);
    const float roughness = look.roughness(at.vector(m.positions), durability, cover);
    out[1] = byte(m.look.size() == m.positions.size() ? weatheredRoughness(roughness, quadAt(at, m.look)) : roughness);
    out[2] = 0;
  });
}

}  // namespace rockbake
