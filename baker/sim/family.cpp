#include "sim/family.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <variant>

#include "core/hash.h"
#include "sim/durability.h"

namespace rockbake {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

// The i-th uniform number of this seed's draw, in [0, 1).
double draw(const SimParams& p, std::uint64_t i) {
  return unitInterval(counterHash(p.seed, purposeId("family"), 0, i));
}
double uniformIn(const Interval& range, double u) {
  return range[0] + (range[1] - range[0]) * u;
}
// Sizes are drawn log-uniformly: ×2 and ×½ are as likely from 1.
double logUniformIn(const Interval& range, double u) {
  return std::exp(uniformIn({std::log(range[0]), std::log(range[1])}, u));
}

// (x, y) turned by `degrees` counter-clockwise.
void turn(double& x, double& y, double degrees) {
  const double c = std::cos(degrees * kDegree), s = std::sin(degrees * kDegree);
  const double tx = c * x - s * y, ty = s * x + c * y;
  x = tx, y = ty;
}

// Rodrigues' rotation of v about the horizontal axis perpendicular to the
// direction `toward` (degrees from +x), so that +z leans towards it by `degrees`.
Vec3d lean(const Vec3d& v, double toward, double degrees) {
  const Vec3d axis{-std::sin(toward * kDegree), std::cos(toward * kDegree), 0.0};
  const double c = std::cos(degrees * kDegree), s = std::sin(degrees * kDegree);
  const Vec3d k_cross_v = cross(axis, v);
  const double k_dot_v = dot(axis, v);
  return {v[0] * c + k_cross_v[0] * s + axis[0] * k_dot_v * (1 - c),
          v[1] * c + k_cross_v[1] * s + axis[1] * k_dot_v * (1 - c),
          v[2] * c + k_cross_v[2] * s + axis[2] * k_dot_v * (1 - c)};
}

// Where along the height the warp is: 0 at the base, 1 at the top (clamped,
// so the warp is defined, and invertible, everywhere).
double along(const Individual& ind, double z) {
  return ind.height > 0 ? std::clamp(z / ind.height, 0.0, 1.0) : 0.0;
}

// The blockout-relative point q (its base centre at 0) in the fitted frame, relative to the pivot.
Vec3d forward(const Individual& ind, const Vec3d& q) {
  Vec3d p{q[0] * ind.scale * ind.stretch[0], q[1] * ind.scale * ind.stretch[1], q[2] * ind.scale * ind.stretch[2]};
  const double t = along(ind, p[2]);
  const double width = 1.0 + ind.taper * (t - 0.5);
  p[0] *= width, p[1] *= width;
  turn(p[0], p[1], ind.twist * t);
  const double offset = ind.bend * ind.height * t * t;
  p[0] += offset * std::cos(ind.bend_toward * kDegree), p[1] += offset * std::sin(ind.bend_toward * kDegree);
  p = lean(p, ind.tilt_toward, ind.tilt);
  turn(p[0], p[1], ind.azimuth);
  return p;
}

Vec3d inverse(const Individual& ind, Vec3d p) {
  turn(p[0], p[1], -ind.azimuth);
  p = lean(p, ind.tilt_toward, -ind.tilt);
  const double t = along(ind, p[2]);
  const double offset = ind.bend * ind.height * t * t;
  p[0] -= offset * std::cos(ind.bend_toward * kDegree), p[1] -= offset * std::sin(ind.bend_toward * kDegree);
  turn(p[0], p[1], -ind.twist * t);
  const double width = 1.0 + ind.taper * (t - 0.5);
  p[0] /= width, p[1] /= width;
  return {p[0] / (ind.scale * ind.stretch[0]), p[1] / (ind.scale * ind.stretch[1]),
          p[2] / (ind.scale * ind.stretch[2])};
}

void drawShape(const SimParams& p, const FamilyParams& f, Individual& ind) {
  ind.scale = logUniformIn(f.scale, draw(p, 0));
  for (std::size_t a = 0; a < 3; ++a) ind.stretch[a] = logUniformIn(f.stretch[a], draw(p, 1 + a));
  ind.azimuth = uniformIn(f.azimuth, draw(p, 4));
  ind.tilt = f.tilt * draw(p, 5);
  ind.tilt_toward = 360.0 * draw(p, 6);
  ind.bend = f.warp.bend * draw(p, 7);
  ind.bend_toward = 360.0 * draw(p, 8);
  ind.taper = f.warp.taper * (2.0 * draw(p, 9) - 1.0);
  ind.twist = f.warp.twist * (2.0 * draw(p, 10) - 1.0);
  ind.height = p.grid.size[2] * ind.scale * ind.stretch[2];
}

void drawCuts(const SimParams& p, const FamilyParams& f, Individual& ind) {
  if (!f.fracture || p.durability.joints.empty()) return;
  const FamilyFracture& fracture = *f.fracture;
  const int span = fracture.cuts[1] - fracture.cuts[0] + 1;
  const int count = fracture.cuts[0] + std::min(span - 1, int(draw(p, 11) * span));
  const double turned = f.geology == FamilyGeology::Turns ? ind.azimuth : 0.0;
  for (int c = 0; c < count; ++c) {
    const std::uint64_t base = 16 + 4 * std::uint64_t(c);
    Individual::Cut cut;
    cut.joint_set = std::min(p.durability.joints.size() - 1, std::size_t(draw(p, base) * p.durability.joints.size()));
    const JointSet& set = p.durability.joints[cut.joint_set];
    // Strikes are clockwise from +y; the azimuth turns counter-clockwise.
    cut.normal = Geology::planeFrame(set.strike - turned, set.dip).normal;
    if (draw(p, base + 1) < 0.5) cut.normal = scale(cut.normal, -1.0);
    cut.depth = uniformIn(fracture.depth, draw(p, base + 2));
    ind.cuts.push_back(cut);
  }
}

// Room for the debris apron beyond the footprint. A talus wedge at the
// colluvium's angle θ around the footprint's perimeter P holding the debris
// volume V_d reaches w = √(2 V_d / (P tan θ)). The debris is at most the yield
// (all of it when rockfall crumbles) times the box the individual fills; the
// catalogue's aprons reach about a third of that bound (bench/README.md,
// "Families"), so the room is half of it, and a voxel to spare.
double apronRoom(const SimParams& p, const Vec3d& extent, double volume, double h) {
  if (!p.grid.ground) return 2 * h;
  const double yield = p.rockfall.mode == RockfallMode::Crumble ? 1.0 : p.colluvium.yield;
  const double perimeter = 2.0 * (extent[0] + extent[1]);
  const double slope = std::tan(p.colluvium.talus_angle * kDegree);
  return 0.5 * std::sqrt(2.0 * yield * volume / (perimeter * slope)) + h;
}

// The blockout's bounding box (its base centre at the origin): the
// primitive's own size, the domain for images and meshes, grown by the
// boundary variation's reach.
Vec3d blockoutBox(const SimParams& p) {
  struct Visitor {
    const Vec3d& domain;
    Vec3d operator()(const BoxShape& b) const { return b.size; }
    Vec3d operator()(const CylinderShape& c) const { return {2 * c.radius, 2 * c.radius, c.height}; }
    Vec3d operator()(const SphereShape& s) const { return {2 * s.radius, 2 * s.radius, 2 * s.radius}; }
    Vec3d operator()(const InsideCornerShape& c) const { return c.size; }
    Vec3d operator()(const ImageShape& i) const { return {domain[0], domain[1], i.height}; }
    Vec3d operator()(const MeshShape&) const { return domain; }
  };
  Vec3d box = std::visit(Visitor{p.grid.size}, p.shape.kind);
  const double pad = p.shape.variation ? p.shape.variation->amplitude : 0.0;
  for (std::size_t a = 0; a < 3; ++a) box[a] += a < 2 ? 2 * pad : pad;
  return box;
}

// The fitted domain: the bounding box of the transformed blockout box
// (sampled on its faces, where the warp's extremes lie), room for the apron
// on every side, and at least the scaled domain height above the ground.
void fitDomain(const SimParams& p, Individual& ind) {
  const Vec3d& declared = p.grid.size;
  const Vec3d size = blockoutBox(p);
  Vec3d lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  constexpr int kSamples = 16;
  for (int i = 0; i <= kSamples; ++i)
    for (int j = 0; j <= kSamples; ++j)
      for (int k = 0; k <= kSamples; ++k) {
        const bool on_face = i == 0 || j == 0 || k == 0 || i == kSamples || j == kSamples || k == kSamples;
        if (!on_face) continue;
        const Vec3d q{size[0] * (double(i) / kSamples - 0.5), size[1] * (double(j) / kSamples - 0.5),
                      size[2] * double(k) / kSamples};
        const Vec3d w = forward(ind, q);
        for (std::size_t a = 0; a < 3; ++a) lo[a] = std::min(lo[a], w[a]), hi[a] = std::max(hi[a], w[a]);
      }
  const double h = std::max({declared[0], declared[1], declared[2]}) / double(p.grid.resolution);
  const Vec3d extent = sub(hi, lo);
  const double volume =
      size[0] * size[1] * size[2] * std::pow(ind.scale, 3) * ind.stretch[0] * ind.stretch[1] * ind.stretch[2];
  ind.apron = apronRoom(p, extent, volume, h);
  ind.domain = {extent[0] + 2 * ind.apron, extent[1] + 2 * ind.apron, std::max(ind.height, hi[2])};
  ind.pivot = {ind.apron - lo[0], ind.apron - lo[1], 0.0};
  // The faces' samples bound the warped box to well within a voxel (a twist turns at most 11.25°
  // between samples); two voxels and 2 % spare.
  for (std::size_t a = 0; a < 3; ++a) {
    const double spare = 2 * h + 0.02 * extent[a];
    ind.box_lo[a] = lo[a] + ind.pivot[a] - spare;
    ind.box_hi[a] = hi[a] + ind.pivot[a] + spare;
  }
}

}  // namespace

Vec3d blockoutBaseCenter(const SimParams& p) {
  const Vec3d& size = p.grid.size;
  return p.shape.center.value_or(Vec3d{size[0] / 2, size[1] / 2, 0.0});
}

Individual drawIndividual(const SimParams& params) {
  Individual ind;
  if (!params.family) {
    ind.domain = params.grid.size;
    ind.pivot = blockoutBaseCenter(params);
    ind.height = params.grid.size[2];
    return ind;
  }
  ind.drawn = true;
  drawShape(params, *params.family, ind);
  drawCuts(params, *params.family, ind);
  fitDomain(params, ind);
  return ind;
}

Vec3d simulationDomain(const SimParams& params) {
  return params.family ? drawIndividual(params).domain : params.grid.size;
}

DurabilityParams individualDurability(const SimParams& params) {
  DurabilityParams d = params.durability;
  if (!params.family || params.family->geology != FamilyGeology::Turns) return d;
  const double azimuth = drawIndividual(params).azimuth;
  if (d.strata) d.strata->strike -= azimuth;
  for (JointSet& j : d.joints) j.strike -= azimuth;
  return d;
}

Vec3d toBlockout(const Individual& individual, const SimParams& params, const Vec3d& world) {
  const Vec3d base = blockoutBaseCenter(params);
  if (!individual.drawn) return world;
  return add(inverse(individual, sub(world, individual.pivot)), base);
}

}  // namespace rockbake
