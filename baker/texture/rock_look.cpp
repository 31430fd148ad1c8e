#include "texture/rock_look.h"

#include <algorithm>

#include "core/hash.h"

namespace rockbake {

namespace {
double inverse(double scale) {
  return scale > 0 ? 1.0 / scale : 0.0;
}
}  // namespace

RockLook::RockLook(std::uint64_t seed, double radius, double voxel_size, std::array<float, 2> durability_range,
                   bool varied)
    : mottle_(counterHash(seed, purposeId("texture-mottle"), 0, 0)),
      variation_(counterHash(seed, purposeId("texture-variation"), 0, 0)),
      grain_(counterHash(seed, purposeId("texture-grain"), 0, 0)),
      colluvium_grain_(counterHash(seed, purposeId("texture-colluvium-grain"), 0, 0)),
      mottle_scale_(inverse(0.25 * radius)),
      variation_scale_(inverse(voxel_size)),
      grain_scale_(inverse(0.02 * radius)),
      colluvium_scale_(inverse(0.015 * radius)),
      varied_(varied),
      durability_min_(durability_range[0]),
      durability_span_(durability_range[1] - durability_range[0]) {}

float RockLook::colourFactor(const std::array<double, 3>& p, float cover) const {
  if (!varied_) return 1.0f;
  const auto at = [&](const PerlinNoise& n, double s) { return s > 0 ? n(p[0] * s, p[1] * s, p[2] * s) : 0.0; };
  const double variation = 0.06 * at(variation_, variation_scale_);
  const double c = std::clamp(double(cover), 0.0, 1.0);
  // Under full cover the rock's terms are weighted 0: not looked up (the result is the same to the bit).
  const double rock =
      c < 1.0 ? 0.10 * mottle_.fractal(p[0] * mottle_scale_, p[1] * mottle_scale_, p[2] * mottle_scale_, 2) +
                    variation + 0.05 * at(grain_, grain_scale_)
              : 0.0;
  const double colluvium = c > 0 ? 0.12 * at(colluvium_grain_, colluvium_scale_) + variation : 0.0;
  return float(1.0 + (1.0 - c) * rock + c * colluvium);
}

float RockLook::normalisedDurability(float durability) const {
  if (durability <= 0.0f) return 0.0f;
  return durability_span_ > 0 ? std::clamp((durability - durability_min_) / durability_span_, 0.0f, 1.0f) : 0.5f;
}

float RockLook::roughness(const std::array<double, 3>& p, float durability, float cover) const {
  const double c = std::clamp(double(cover), 0.0, 1.0);
  // As in colourFactor: the grain is weighted 0 under full cover, so it is not looked up there.
  const double grain = varied_ && grain_scale_ > 0 && c < 1.0
                           ? grain_(p[0] * grain_scale_, p[1] * grain_scale_, p[2] * grain_scale_)
                           : 0.0;
  const double rock = 0.9 - 0.15 * normalisedDurability(durability) + 0.04 * grain;
  return float(std::clamp((1.0 - c) * rock + c * 0.95, 0.0, 1.0));
}

float weatheredRoughness(float roughness, const std::array<double, 4>& look) {
  const auto towards = [](double from, double to, double t) { return from + (to - from) * std::clamp(t, 0.0, 1.0); };
  double r = roughness;
  r = towards(r, 0.55, 0.5 * look[1]);
  r = towards(r, 0.35, 0.6 * look[2]);
  r = towards(r, 0.97, look[3]);
  return float(r);
}

}  // namespace rockbake
