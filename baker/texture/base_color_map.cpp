#include <algorithm>
#include <cmath>

#include "platform/colour.h"
#include "texture/bake_maps.h"
#include "texture/texel_walk.h"

namespace rockbake {

using namespace texture_detail;

TextureImage<std::uint8_t> bakeBaseColor(const LodBake& bake, const RockLook& look) {
  return walkTexels<std::uint8_t>(bake, 3, [&](std::size_t, const TexelSample& s, std::uint8_t* out) {
    const SurfacePoint& at = s.hit ? s.source : s.lod;
    const SurfaceMesh& m = *at.mesh;
    const Vec3d colour = m.colors.size() == m.positions.size() ? at.vector(m.colors) : Vec3d{0.18, 0.18, 0.18};
    const float cover = s.surface == 1                             ? 1.0f
                        : m.colluvium.size() == m.positions.size() ? float(at.scalar(m.colluvium))
                                                                   : 0.0f;
    const double factor = look.colourFactor(at.vector(m.positions), cover);
    for (int k = 0; k < 3; ++k) out[k] = linearToSrgbByte(float(colour[std::size_t(k)] * factor));
  });
}

}  // namespace rockbake
