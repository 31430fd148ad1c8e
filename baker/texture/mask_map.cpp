#include <algorithm>
#include <cmath>

#include "texture/bake_maps.h"
#include "texture/texel_walk.h"

namespace rockbake {

using namespace texture_detail;

TextureImage<std::uint8_t> bakeMask(const LodBake& bake, const RockLook& look) {
  const auto byte = [](double v) { return std::uint8_t(std::lround(std::clamp(v, 0.0, 1.0) * 255.0)); };
  return walkTexels<std::uint8_t>(bake, 4, [&](std::size_t, const TexelSample& s, std::uint8_t* out) {
    const SurfacePoint& at = s.hit ? s.source : s.lod;
    const SurfaceMesh& m = *at.mesh;
    const auto attribute = [&](const std::vector<float>& values, double otherwise) {
      return values.size() == m.positions.size() ? at.scalar(values) : otherwise;
    };
    out[0] = byte(s.surface == 1 ? 0.0 : look.normalisedDurability(float(attribute(m.durability, 0.0))));
    out[1] = byte(s.surface == 1 ? 1.0 : attribute(m.colluvium, 0.0));
    out[2] = byte(attribute(m.curvature, 0.5));
    out[3] = byte(attribute(m.altitude, 0.0));
  });
}

}  // namespace rockbake
