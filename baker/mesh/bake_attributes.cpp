#include "mesh/bake_attributes.h"

#include "platform/colour.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <tbb/parallel_for.h>

#include "core/hash.h"
#include "core/perlin_noise.h"

namespace rockbake {
namespace {

using Rgb = std::array<float, 3>;

Rgb lerp(const Rgb& a, const Rgb& b, float t) {
  return {a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t, a[2] + (b[2] - a[2]) * t};
}

// Piecewise-linear ramp through evenly spaced stops, t in [0, 1].
template <std::size_t N>
Rgb ramp(const std::array<Rgb, N>& stops, float t) {
  t = std::clamp(t, 0.0f, 1.0f) * float(N - 1);
  const std::size_t i = std::min(std::size_t(t), N - 2);
  return lerp(stops[i], stops[i + 1], t - float(i));
}

// Palette colours are sRGB; they become scene-linear through the project's
// OpenColorIO config (docs/rendering.md), the same transform the render previews invert.
Rgb srgb(float r, float g, float b) {
  return srgbToSceneLinear({r, g, b});
}

// A rock voxel's history as fractions of a run of `cycles` cycles (bake_attributes.h).
std::array<float, 3> voxelHistory(const VoxelHistory& h, std::size_t cell, int cycles) {
  const float n = float(cycles);
  const float exposed = h.exposed[cell], scarred = h.scarred[cell];
  // Weathering never stops, so most of a surface is young: the age saturates over a quarter of
  // the run, so that rock a few cycles old already shows it (1 − e⁻⁴ for the blockout's surface).
  return {exposed < 0.0f ? 0.0f : 1.0f - std::exp(-4.0f * std::max(n - exposed, 0.0f) / n),
          scarred < 0.0f ? 0.0f : std::clamp(1.0f - (n - scarred) / n, 0.0f, 1.0f),
          std::clamp(h.covered_for[cell] / (n + 1.0f), 0.0f, 1.0f)};
}

void sampleSurface(SurfaceMesh& m, const AttributeSources& src, bool is_colluvium) {
  const VoxelRock& rock = *src.rock;
  const GridLayout& g = rock.layout;
  const std::size_t n = m.positions.size();
  m.durability.assign(n, 0.0f);
  m.colluvium.assign(n, is_colluvium ? 1.0f : 0.0f);
  m.curvature.assign(n, 0.5f);
  m.altitude.assign(n, 0.0f);
  const bool history = src.history && !rock.history.empty();
  const int cycles = std::max(rock.history.cycles, 1);
  if (history) m.history.assign(n, {0.0f, 0.0f, 0.0f});
  const auto material = [&](int x, int y, int z) {
    if (!g.contains(x, y, z)) return (z < 0 && g.ground) ? Material::Rock : Material::Air;
    return rock.material[g.index(x, y, z)];
  };
  const auto isRock = [&](int x, int y, int z) { return g.contains(x, y, z) && material(x, y, z) == Material::Rock; };
  const auto exposed = [&](int x, int y, int z) {
    return isRock(x, y, z) && (material(x - 1, y, z) != Material::Rock || material(x + 1, y, z) != Material::Rock ||
                               material(x, y - 1, z) != Material::Rock || material(x, y + 1, z) != Material::Rock ||
                               material(x, y, z - 1) != Material::Rock || material(x, y, z + 1) != Material::Rock);
  };
  // The nearest voxel (by centre) satisfying `want` within `radius` voxels of p, or -1.
  const auto nearest = [&](const std::array<float, 3>& p, int radius, auto&& want) -> long {
    const double fx = (p[0] - g.origin[0]) / g.h, fy = (p[1] - g.origin[1]) / g.h, fz = (p[2] - g.origin[2]) / g.h;
    const int cx = int(std::floor(fx)), cy = int(std::floor(fy)), cz = int(std::floor(fz));
    double best = std::numeric_limits<double>::max();
    long found = -1;
    for (int z = cz - radius; z <= cz + radius; ++z)
      for (int y = cy - radius; y <= cy + radius; ++y)
        for (int x = cx - radius; x <= cx + radius; ++x) {
          if (!want(x, y, z)) continue;
          const double dx = x + 0.5 - fx, dy = y + 0.5 - fy, dz = z + 0.5 - fz;
          const double d = dx * dx + dy * dy + dz * dz;
          if (d < best) best = d, found = long(g.index(x, y, z));
        }
    return found;
  };

  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t v = r.begin(); v != r.end(); ++v) {
      const auto& p = m.positions[v];
      m.altitude[v] = float(std::clamp(p[2] / g.domain_height, 0.0, 1.0));
      if (is_colluvium) continue;
      long i = -1;
      for (int radius = 1; radius <= 4 && i < 0; radius += 3) i = nearest(p, radius, isRock);
      if (i >= 0) m.durability[v] = rock.durability[std::size_t(i)];
      long e = -1;
      for (int radius = 1; radius <= 4 && e < 0; radius += 3) e = nearest(p, radius, exposed);
      if (e >= 0) m.curvature[v] = std::clamp((*src.exposure)[std::size_t(e)], 0.0f, 1.0f);
      if (history && e >= 0) m.history[v] = voxelHistory(rock.history, std::size_t(e), cycles);
      // Colluvium coverage: colluvium among the non-rock voxels of the 3×3×3 block.
      const int cx = int(std::floor((p[0] - g.origin[0]) / g.h)), cy = int(std::floor((p[1] - g.origin[1]) / g.h)),
                cz = int(std::floor((p[2] - g.origin[2]) / g.h));
      int open = 0, covered = 0;
      for (int z = cz - 1; z <= cz + 1; ++z)
        for (int y = cy - 1; y <= cy + 1; ++y)
          for (int x = cx - 1; x <= cx + 1; ++x) {
            const Material mat = material(x, y, z);
            if (mat == Material::Rock) continue;
            ++open;
            covered += mat == Material::Colluvium;
          }
      m.colluvium[v] = open > 0 ? float(covered) / float(open) : 0.0f;
    }
  });
}

void tint(SurfaceMesh& m, const PaletteParams& p);

void paint(SurfaceMesh& m, const PaletteParams& p) {
  static const std::array<Rgb, 5> kDebug{Rgb{0, 0, 1}, Rgb{0, 1, 1}, Rgb{0, 1, 0}, Rgb{1, 1, 0}, Rgb{1, 0, 0}};
  static const Rgb kPurple{0.5f, 0.0f, 0.5f};
  static const std::array<Rgb, 3> kCurvature{Rgb{0.02f, 0.1f, 0.8f}, Rgb{0.8f, 0.8f, 0.8f}, Rgb{0.8f, 0.02f, 0.02f}};
  // Sandstone, soft to durable (sRGB #E3C9A0, #C98A55, #A0563A, #6E3B2A); colluvium #B49A78.
  static const std::array<Rgb, 4> kNatural{srgb(0.890f, 0.788f, 0.627f), srgb(0.788f, 0.541f, 0.333f),
                                           srgb(0.627f, 0.337f, 0.227f), srgb(0.431f, 0.231f, 0.165f)};
  static const Rgb kSand = srgb(0.706f, 0.604f, 0.471f);
  const Rgb colluvium_color = p.colluvium_color ? srgb(float((*p.colluvium_color)[0]), float((*p.colluvium_color)[1]),
                                                       float((*p.colluvium_color)[2]))
                                                : kSand;
  // The preset's layers, keyed by durability, interpolated in linear light
  // (converted once: an OCIO conversion per vertex cost more than the rest of the paint).
  std::vector<Rgb> linear_layers;
  for (const PaletteLayer& l : p.layers)
    linear_layers.push_back(srgb(float(l.color[0]), float(l.color[1]), float(l.color[2])));
  const auto layerColor = [&p, &linear_layers](float d) {
    const auto& layers = p.layers;
    if (d <= layers.front().durability) return linear_layers.front();
    for (std::size_t i = 1; i < layers.size(); ++i)
      if (d <= layers[i].durability) {
        const float t = float((d - layers[i - 1].durability) / (layers[i].durability - layers[i - 1].durability));
        return lerp(linear_layers[i - 1], linear_layers[i], t);
      }
    return linear_layers.back();
  };
  const float span = std::max(p.durability_max - p.durability_min, 1e-6f);
  m.colors.resize(m.positions.size());
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    const float t = (m.durability[v] - p.durability_min) / span;
    const float c = std::clamp(m.colluvium[v], 0.0f, 1.0f);
    switch (p.palette) {
      case Palette::Debug:
        m.colors[v] = lerp(ramp(kDebug, t), kPurple, c);
        break;
      case Palette::Curvature:
        m.colors[v] = ramp(kCurvature, m.curvature[v]);
        break;
      case Palette::Natural:
        m.colors[v] = lerp(p.layers.empty() ? ramp(kNatural, t) : layerColor(m.durability[v]), colluvium_color, c);
        break;
    }
    for (float& x : m.colors[v]) x = std::clamp(x, 0.0f, 1.0f);
  }
  if (p.palette == Palette::Natural && p.look && m.look.size() == m.positions.size()) tint(m, p);
}

float smoothstep(float lo, float hi, float x) {
  const float t = std::clamp((x - lo) / (hi - lo), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

// The look's tint on every vertex (lookTint), with lichen in patches a few voxels across on
// long-exposed rock facing up.
void tint(SurfaceMesh& m, const PaletteParams& p) {
  const LookParams& look = *p.look;
  const LookColours colours = lookColours(look);
  const PerlinNoise patches(counterHash(p.seed, purposeId("look-lichen"), 0, 0));
  const double scale = 1.0 / (3.0 * p.voxel);
  const bool normals = m.normals.size() == m.positions.size();
  tbb::parallel_for(std::size_t(0), m.positions.size(), [&](std::size_t v) {
    float lichen = 0.0f;
    if (look.lichen > 0 && normals && m.name != "colluvium") {
      const auto& q = m.positions[v];
      const float patch = float(patches.fractal(q[0] * scale, q[1] * scale, q[2] * scale, 2));
      const float age = m.look[v][0];
      lichen = std::clamp(
          float(look.lichen) * smoothstep(0.3f, 0.8f, m.normals[v][2]) * age * age * smoothstep(0.05f, 0.3f, patch),
          0.0f, 1.0f);
    }
    const float scar = m.history.size() == m.positions.size() ? m.history[v][1] : 0.0f;
    m.colors[v] = lookTint(m.colors[v], m.look[v], scar, lichen, look, colours);
  });
}

}  // namespace

AssetMeshes sampleAttributes(AssetMeshes meshes, const AttributeSources& sources) {
  sampleSurface(meshes.rock, sources, false);
  sampleSurface(meshes.colluvium, sources, true);
  return meshes;
}

PaletteParams paletteParams(const VoxelRock& rock, const VertexPaletteParams& bake) {
  PaletteParams p;
  p.palette = bake.palette;
  p.layers = bake.layers;
  p.colluvium_color = bake.colluvium_color;
  float lo = std::numeric_limits<float>::max(), hi = std::numeric_limits<float>::lowest();
  for (std::size_t i = 0; i < rock.material.size(); ++i)
    if (rock.material[i] == Material::Rock)
      lo = std::min(lo, rock.durability[i]), hi = std::max(hi, rock.durability[i]);
  if (lo <= hi) p.durability_min = lo, p.durability_max = hi;
  return p;
}

LookColours lookColours(const LookParams& look) {
  const auto linear = [](const SrgbColor& c) { return srgb(float(c[0]), float(c[1]), float(c[2])); };
  return {linear(look.stain_color), linear(look.varnish_color), linear(look.dust_color), linear(look.lichen_color)};
}

std::array<float, 3> lookTint(std::array<float, 3> c, const std::array<float, 4>& look, float scar, float lichen,
                              const LookParams& params, const LookColours& colours) {
  const float age = std::clamp(look[0], 0.0f, 1.0f), stain = std::clamp(look[1], 0.0f, 1.0f);
  const float wet = std::clamp(look[2], 0.0f, 1.0f), dust = std::clamp(look[3], 0.0f, 1.0f);
  const float pale =
      1.0f + float(params.scars) * (0.15f * (1.0f - age) * (1.0f - age) + 0.3f * std::clamp(scar, 0.0f, 1.0f));
  for (float& x : c) x *= pale;
  c = lerp(c, lerp(colours.stain, colours.varnish, age), 0.85f * stain);
  c = lerp(c, colours.dust, 0.8f * dust);
  c = lerp(c, colours.lichen, lichen);
  for (float& x : c) x = std::clamp(x * (1.0f - 0.35f * wet), 0.0f, 1.0f);
  return c;
}

AssetMeshes applyPalette(AssetMeshes meshes, const PaletteParams& params) {
  paint(meshes.rock, params);
  paint(meshes.colluvium, params);
  return meshes;
}

}  // namespace rockbake
