// Ken Perlin's improved noise (2002) with a permutation shuffled from a seed: the one
// seeded noise the stages share (durability beds, shape variation, surface detail, the
// look's mottling). A pure function of (seed, point), like every random choice
// (docs/model.md §10).
#pragma once

#include <array>
#include <cstdint>

namespace rockbake {

// Values lie in about [-1, 1]; 0 at integer lattice points.
class PerlinNoise {
 public:
  explicit PerlinNoise(std::uint64_t seed);
  double operator()(double x, double y, double z) const;
  // Octaves summed at doubling frequency and halving amplitude, normalised to [-1, 1].
  double fractal(double x, double y, double z, int octaves) const;

 private:
  std::array<std::uint8_t, 512> perm_;
};

}  // namespace rockbake
