#include "texture/bake_maps.h"
#include "texture/texel_walk.h"

namespace rockbake {

using namespace texture_detail;

TextureImage<float> bakeHeight(const LodBake& bake) {
  return walkTexels<float>(bake, 1,
                           [&](std::size_t, const TexelSample& s, float* out) { out[0] = s.hit ? s.distance : 0.0f; });
}

}  // namespace rockbake
