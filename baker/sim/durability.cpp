#include "sim/durability.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <tbb/parallel_for.h>

#include "core/hash.h"

namespace rockbake {

PerlinNoise::PerlinNoise(std::uint64_t seed) {
  std::array<std::uint8_t, 256> p;
  std::iota(p.begin(), p.end(), 0);
  // Fisher–Yates driven by the counter hash: the table depends on the seed only.
  for (int i = 255; i > 0; --i) {
    const std::uint64_t bits = counterHash(seed, purposeId("perlin-permutation"), 0, std::uint64_t(i));
    std::swap(p[std::size_t(i)], p[std::size_t(bits % std::uint64_t(i + 1))]);
  }
  for (std::size_t i = 0; i < 512; ++i) perm_[i] = p[i & 255];
}

namespace {

inline double fade(double t) {
  return t * t * t * (t * (t * 6 - 15) + 10);
}
inline double lerp(double t, double a, double b) {
  return a + t * (b - a);
}
// The 12 edge directions of a cube (plus 4 repeats), as in the reference implementation.
inline double grad(int hash, double x, double y, double z) {
  const int h = hash & 15;
  const double u = h < 8 ? x : y;
  const double v = h < 4 ? y : (h == 12 || h == 14 ? x : z);
  return ((h & 1) ? -u : u) + ((h & 2) ? -v : v);
}

}  // namespace

double PerlinNoise::operator()(double x, double y, double z) const {
  const double fx = std::floor(x), fy = std::floor(y), fz = std::floor(z);
  const int X = int(std::int64_t(fx) & 255), Y = int(std::int64_t(fy) & 255), Z = int(std::int64_t(fz) & 255);
  x -= fx, y -= fy, z -= fz;
  const double u = fade(x), v = fade(y), w = fade(z);
  const auto& p = perm_;
  const int A = p[X] + Y, AA = p[A] + Z, AB = p[A + 1] + Z;
  const int B = p[X + 1] + Y, BA = p[B] + Z, BB = p[B + 1] + Z;
  return lerp(w,
              lerp(v, lerp(u, grad(p[AA], x, y, z), grad(p[BA], x - 1, y, z)),
                   lerp(u, grad(p[AB], x, y - 1, z), grad(p[BB], x - 1, y - 1, z))),
              lerp(v, lerp(u, grad(p[AA + 1], x, y, z - 1), grad(p[BA + 1], x - 1, y, z - 1)),
                   lerp(u, grad(p[AB + 1], x, y - 1, z - 1), grad(p[BB + 1], x - 1, y - 1, z - 1))));
}

double PerlinNoise::fractal(double x, double y, double z, int octaves) const {
  double sum = 0.0, norm = 0.0, amplitude = 1.0, frequency = 1.0;
  for (int o = 0; o < octaves; ++o) {
    sum += amplitude * (*this)(x * frequency, y * frequency, z * frequency);
    norm += amplitude;
    amplitude *= 0.5;
    frequency *= 2.0;
  }
  return sum / norm;
}

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

void assignDurability(VoxelRock& rock, const DurabilityField& field) {
  const GridLayout& g = rock.layout;
  tbb::parallel_for(0, g.nz, [&](int z) {
    const double altitude = g.altitude(z);
    for (int y = 0; y < g.ny; ++y)
      for (int x = 0; x < g.nx; ++x) {
        const std::size_t i = g.index(x, y, z);
        rock.durability[i] = rock.material[i] == Material::Rock ? float(field.at(g.center(x, y, z), altitude)) : 0.f;
      }
  });
}

}  // namespace rockbake
