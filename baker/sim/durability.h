// The durability graph (SPEC §2.4): durability as a function of altitude,
// with seeded improved Perlin noise per segment.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/voxel_rock.h"
#include "preset/preset.h"

namespace rockbake {

// Durability never falls below this, whatever the noise does.
inline constexpr double kMinDurability = 0.01;

// Ken Perlin's improved noise (2002) with a permutation shuffled from a seed.
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

// A graph ready to evaluate: the preset graph plus one noise field per segment.
class DurabilityField {
 public:
  // `stream` separates the base graph (0) from keyframe i (i + 1) so each has its own noise.
  DurabilityField(const DurabilityGraph& graph, std::uint64_t seed, std::uint64_t stream);

  double graphAt(double altitude) const;  // the polyline alone
  // Durability at a world position with normalised altitude `altitude`.
  double at(const Vec3d& world, double altitude) const;

 private:
  DurabilityGraph graph_;
  std::vector<PerlinNoise> noise_;  // one per segment (unused where the segment has none)
};

// Sets the durability of every rock voxel from `field`; other voxels get 0.
void assignDurability(VoxelRock& rock, const DurabilityField& field);

}  // namespace rockbake
