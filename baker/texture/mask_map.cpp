#include <algorithm>
#include <cmath>

#include "texture/bake_maps.h"
#include "texture/texel_walk.h"

namespace rockbake {

using namespace texture_detail;

GroundMask groundMask(const AssetMeshes& source, std::optional<double> ground, double voxel) {
  GroundMask mask;
  if (!ground || voxel <= 0) return mask;
  mask.ground = *ground;
  mask.feather = kGroundFeather * voxel;
  const std::vector<std::array<double, 2>> contact = groundContactPoints(source, *ground, 1e-4 * voxel, 0.75 * voxel, 0.5 * voxel);
  if (contact.empty()) return mask;
  mask.contact = std::make_shared<PlaneDistance>(
      contact, std::array<double, 2>{double(source.bounds_min[0]), double(source.bounds_min[1])},
      std::array<double, 2>{double(source.bounds_max[0]), double(source.bounds_max[1])}, 0.5 * voxel);
  return mask;
}

double GroundMask::at(const Vec3d& p) const {
  if (!contact) return 0.0;
  const double across = contact->at(p[0], p[1]), up = p[2] - ground;
  const double t = std::clamp(std::sqrt(across * across + up * up) / feather, 0.0, 1.0);
  return 1.0 - t * t * (3.0 - 2.0 * t);
}

TextureImage<std::uint8_t> bakeMask(const LodBake& bake, const RockLook& look, const GroundMask& ground) {
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
    out[3] = byte(ground.at(at.vector(m.positions)));
  });
}

}  // namespace rockbake
