// The durability field (docs/model.md §4): the graph over altitude with seeded
// improved Perlin noise per segment, read along tilted and folded beds
// (strata), weakened along joints and hardened in a rind.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/perlin_noise.h"
#include "core/voxel_rock.h"
#include "preset/preset.h"

namespace rockbake {

// Durability never falls below this, whatever the noise does.
inline constexpr double kMinDurability = 0.01;

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

// The rock's structure (strata, joints, rind), fixed for a whole run: every
// graph, the first and each keyframe's, is read through it. Planes are
// measured through the centre of the domain (grid.size); random choices come
// from (seed, purpose, set, plane).
class Geology {
 public:
  Geology(const DurabilityParams& params, const Vec3d& domain, std::uint64_t seed);

  bool tilted() const { return strata_.has_value(); }
  bool jointed() const { return !joints_.empty(); }
  bool hasRind() const { return rind_.has_value(); }
  const std::optional<RindParams>& rind() const { return rind_; }

  // The altitude the graph is read at: the position along the beds' normal
  // through the domain's centre, normalised by the domain's height, folded by
  // the warp; z / height when the beds lie flat and unwarped.
  double bedAltitude(const Vec3d& world) const;
  // Signed distance (world units) along set `set`'s normal from `world` to its nearest plane.
  double jointDistance(std::size_t set, const Vec3d& world) const;
  // How many times faster rock weathers at a voxel of edge h centred at
  // `world` because of the joints: 1 / factor inside a joint zone, 1 away from
  // them, blended by the part of the voxel the zone covers (so a joint thinner
  // than a voxel still weakens it); sets multiply.
  double jointRate(const Vec3d& world, double h) const;
  // The same for the rind, given the part of the voxel within its depth (0..1).
  double rindRate(double coverage) const;

  struct Frame {
    Vec3d normal, along_strike, across;  // unit vectors; the normal points up
  };
  // Planes striking `strike` degrees clockwise from +y (seen from above) and
  // dipping `dip` degrees towards the strike's right.
  static Frame planeFrame(double strike, double dip);

 private:
  struct JointField {
    JointSet params;
    Frame frame;
    double offset;  // plane k sits at (k + offset) · spacing + jitter_k along the normal
  };
  double planePosition(const JointField& set, std::size_t index, long long k) const;

  Vec3d center_{};
  double height_ = 1.0;
  std::uint64_t seed_ = 0;
  std::optional<StrataParams> strata_;
  Frame beds_{};
  std::optional<PerlinNoise> warp_;
  std::array<double, 2> warp_offset_{};
  std::vector<JointField> joints_;
  std::optional<RindParams> rind_;
};

// The part (0..255) of each rock voxel lying within `depth` (world units) of
// the rock's surface, air and colluvium counting as outside and the ground as
// inside; 0 off rock. Computed from the initial rock: the rind's extent.
std::vector<std::uint8_t> rindCoverage(const VoxelRock& rock, double depth);

// How far (world units) from the surface rindCoverage reads its signed
// distance, on a grid of voxel size h: the depth and a voxel.
inline double rindReach(double depth, double h) {
  return depth + h;
}

// Sets the durability of every rock voxel from `field` read through
// `geology` (rock.rind holds the rind's coverage when the geology has one);
// other voxels get 0.
void assignDurability(VoxelRock& rock, const DurabilityField& field, const Geology& geology);

}  // namespace rockbake
