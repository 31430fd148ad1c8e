#include "sim/durability.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include <tbb/parallel_for.h>

#include "core/hash.h"
#include "core/vec3.h"
#include "sim/distance_field.h"

namespace rockbake {

DurabilityField::DurabilityField(const DurabilityGraph& graph, std::uint64_t seed, std::uint64_t stream)
    : graph_(graph) {
  const std::size_t segments = graph.points.empty() ? 0 : graph.points.size() - 1;
  for (std::size_t s = 0; s < segments; ++s)
    noise_.emplace_back(counterHash(seed, purposeId("durability-noise"), stream, s));
}

double DurabilityField::graphAt(double a) const {
  const auto& pts = graph_.points;
  if (a <= pts.front()[0]) return pts.front()[1];
  if (a >= pts.back()[0]) return pts.back()[1];
  for (std::size_t i = 1; i < pts.size(); ++i) {
    if (a <= pts[i][0]) {
      const double t = (a - pts[i - 1][0]) / (pts[i][0] - pts[i - 1][0]);
      return pts[i - 1][1] + t * (pts[i][1] - pts[i - 1][1]);
    }
  }
  return pts.back()[1];
}

double DurabilityField::at(const Vec3d& world, double a) const {
  double d = graphAt(a);
  const auto& pts = graph_.points;
  // Noise belongs to the segment whose altitude range holds a (the lower one on a shared point).
  for (std::size_t s = 0; s + 1 < pts.size() && s < graph_.noise.size(); ++s) {
    if (a >= pts[s][0] && a <= pts[s + 1][0]) {
      if (const auto& n = graph_.noise[s]) {
        d += n->amplitude *
             noise_[s].fractal(world[0] / n->period, world[1] / n->period, world[2] / n->period, n->octaves);
      }
      break;
    }
  }
  return std::max(d, kMinDurability);
}

namespace {

constexpr double kRadiansPerDegree = M_PI / 180.0;

// The part of [t - h/2, t + h/2] (a voxel's extent along a plane's normal) within w of the plane at 0.
double zoneCoverage(double t, double w, double h) {
  const double a = std::abs(t);
  return std::clamp((std::min(a + h / 2, w) - std::max(a - h / 2, -w)) / h, 0.0, 1.0);
}

// Rates blend, not durabilities: a voxel part soft, part hard retreats at the
// mean of the parts' rates.
double blendedRate(double coverage, double factor) {
  return coverage / factor + (1.0 - coverage);
}

}  // namespace

Geology::Frame Geology::planeFrame(double strike, double dip) {
  const double s = strike * kRadiansPerDegree, d = dip * kRadiansPerDegree;
  const Vec3d along{std::sin(s), std::cos(s), 0.0};
  const Vec3d down_dip{std::cos(s), -std::sin(s), 0.0};  // horizontal, to the strike's right
  const Vec3d normal{std::sin(d) * down_dip[0], std::sin(d) * down_dip[1], std::cos(d)};
  const Vec3d across = cross(normal, along);
  return {normal, along, across};
}

Geology::Geology(const DurabilityParams& params, const Vec3d& domain, std::uint64_t seed)
    : center_{domain[0] / 2, domain[1] / 2, domain[2] / 2},
      height_(domain[2]),
      seed_(seed),
      strata_(params.strata),
      rind_(params.rind) {
  if (strata_) {
    beds_ = planeFrame(strata_->strike, strata_->dip);
    if (strata_->warp_amplitude > 0) {
      warp_.emplace(counterHash(seed, purposeId("strata-warp"), 0, 0));
      // Off the lattice, where Perlin noise is 0 for every seed.
      for (std::size_t a = 0; a < 2; ++a)
        warp_offset_[a] = 64.0 * unitInterval(counterHash(seed, purposeId("strata-warp-offset"), 0, a));
    }
  }
  for (std::size_t j = 0; j < params.joints.size(); ++j) {
    const JointSet& set = params.joints[j];
    joints_.push_back(
        {set, planeFrame(set.strike, set.dip), unitInterval(counterHash(seed, purposeId("joint-offset"), j, 0))});
  }
}

double Geology::bedAltitude(const Vec3d& world) const {
  const Vec3d p = sub(world, center_);
  double along_normal = dot(p, beds_.normal);
  if (warp_) {
    // A fold moves the beds along their normal by the same amount through
    // their whole thickness: noise over the bedding plane only.
    const double u = dot(p, beds_.along_strike) / strata_->warp_period + warp_offset_[0];
    const double v = dot(p, beds_.across) / strata_->warp_period + warp_offset_[1];
    along_normal -= strata_->warp_amplitude * warp_->fractal(u, v, 0.5, 2);
  }
  return 0.5 + along_normal / height_;
}

double Geology::planePosition(const JointField& set, std::size_t index, long long k) const {
  const double jitter = unitInterval(counterHash(seed_, purposeId("joint-jitter"), index, std::uint64_t(k)));
  return (double(k) + set.offset) * set.params.spacing + (jitter - 0.5) * set.params.jitter;
}

double Geology::jointDistance(std::size_t index, const Vec3d& world) const {
  const JointField& set = joints_[index];
  const double t = dot(sub(world, center_), set.frame.normal);
  // Planes move at most jitter / 2 < spacing / 2 from their regular place: the
  // nearest is among the regular places' neighbours.
  const long long k0 = (long long)std::floor(t / set.params.spacing - set.offset);
  double best = std::numeric_limits<double>::infinity();
  for (long long k = k0 - 1; k <= k0 + 2; ++k) {
    const double d = t - planePosition(set, index, k);
    if (std::abs(d) < std::abs(best)) best = d;
  }
  return best;
}

double Geology::jointRate(const Vec3d& world, double h) const {
  double rate = 1.0;
  for (std::size_t j = 0; j < joints_.size(); ++j) {
    const double c = zoneCoverage(jointDistance(j, world), joints_[j].params.width, h);
    if (c > 0) rate *= blendedRate(c, joints_[j].params.factor);
  }
  return rate;
}

double Geology::rindRate(double coverage) const {
  return rind_ && coverage > 0 ? blendedRate(coverage, rind_->factor) : 1.0;
}

std::vector<std::uint8_t> rindCoverage(const VoxelRock& rock, double depth) {
  const GridLayout& g = rock.layout;
  std::vector<std::uint8_t> inside(g.cellCount());
  for (std::size_t i = 0; i < inside.size(); ++i) inside[i] = rock.material[i] == Material::Rock;
  const SignedDistanceField distance = signedDistance(inside, g, rindReach(depth, g.h));
  std::vector<std::uint8_t> coverage(g.cellCount(), 0);
  tbb::parallel_for(std::size_t(0), coverage.size(), [&](std::size_t i) {
    if (!inside[i]) return;
    // The voxel spans depths [d - h/2, d + h/2] below the surface.
    const double d = -distance[i];
    const double part = std::clamp((depth - (d - g.h / 2)) / g.h, 0.0, 1.0);
    coverage[i] = std::uint8_t(std::lround(part * 255.0));
  });
  return coverage;
}

void assignDurability(VoxelRock& rock, const DurabilityField& field, const Geology& geology) {
  const GridLayout& g = rock.layout;
  const bool rind = geology.hasRind() && !rock.rind.empty();
  tbb::parallel_for(0, g.nz, [&](int z) {
    const double altitude = g.altitude(z);
    for (int y = 0; y < g.ny; ++y)
      for (int x = 0; x < g.nx; ++x) {
        const std::size_t i = g.index(x, y, z);
        const std::size_t row = std::size_t(y) + std::size_t(g.ny) * std::size_t(z);
        if (rock.material[i] != Material::Rock) {
          rock.durability.set(row, x, 0.f);
          continue;
        }
        const Vec3d p = g.center(x, y, z);
        double d = field.at(p, geology.tilted() ? geology.bedAltitude(p) : altitude);
        if (geology.jointed()) d /= geology.jointRate(p, g.h);
        if (rind) d /= geology.rindRate(rock.rind[i] / 255.0);
        rock.durability.set(row, x, float(std::max(d, kMinDurability)));
      }
  });
}

}  // namespace rockbake
