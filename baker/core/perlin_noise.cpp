#include "core/perlin_noise.h"

#include <cmath>
#include <numeric>
#include <utility>

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
// The 12 edge directions of a cube (plus 4 repeats), as in the reference implementation,
// as a table: the reference picks and negates two of x, y, z with branches on the hash, which
// the processor cannot predict (a quarter of the noise's time went to them). The table's sum
// has the same value: its third term is ±0.
constexpr double kGradient[16][3] = {{1, 1, 0},  {-1, 1, 0},  {1, -1, 0}, {-1, -1, 0}, {1, 0, 1},  {-1, 0, 1},
                                     {1, 0, -1}, {-1, 0, -1}, {0, 1, 1},  {0, -1, 1},  {0, 1, -1}, {0, -1, -1},
                                     {1, 1, 0},  {0, -1, 1},  {-1, 1, 0}, {0, -1, -1}};
inline double grad(int hash, double x, double y, double z) {
  const double* g = kGradient[hash & 15];
  return g[0] * x + g[1] * y + g[2] * z;
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

}  // namespace rockbake
