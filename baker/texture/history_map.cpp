#include <algorithm>
#include <cmath>

#include "texture/bake_maps.h"
#include "texture/texel_walk.h"

namespace rockbake {

using namespace texture_detail;

TextureImage<std::uint8_t> bakeHistory(const LodBake& bake) {
  const auto byte = [](double v) { return std::uint8_t(std::lround(std::clamp(v, 0.0, 1.0) * 255.0)); };
  return walkTexels<std::uint8_t>(bake, 4, [&](std::size_t, const TexelSample& s, std::uint8_t* out) {
    const SurfacePoint& at = s.hit ? s.source : s.lod;
    const SurfaceMesh& m = *at.mesh;
    const std::array<double, 4> look =
        m.look.size() == m.positions.size() ? quadAt(at, m.look) : std::array<double, 4>{0, 0, 0, 0};
    for (std::size_t k = 0; k < 4; ++k) out[k] = byte(look[k]);
  });
}

}  // namespace rockbake
