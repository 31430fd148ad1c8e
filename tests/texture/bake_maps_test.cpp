// The maps (texture/bake_maps.h): a tangent-space round trip decoded by glTF's rules in this
// file's own code, occlusion in a crevice and on open ground, each layer's colour where the
// layer is, the rasteriser's shared-edge rule, tangent handedness, and byte-identical files at
// one and two threads.
#include <gtest/gtest.h>
#include <png.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <csetjmp>
#include <cstring>

#include "core/vec3.h"
#include "exr_image.h"
#include "mesh/simplify_lods.h"
#include "platform/colour.h"
#include "texture/ambient_occlusion.h"
#include "texture/bake_maps.h"
#include "texture/dilate_texels.h"
#include "texture/rasterize_uv.h"
#include "texture/ray_source.h"
#include "texture/tangents.h"
#include "texture/texture_files.h"
#include "texture/texture_set.h"
#include "texture/trace_texels.h"
#include "texture/uv_atlas.h"
#include "texture_fixtures.h"

namespace rockbake {
namespace {

using V = std::array<double, 3>;
V add(const V& a, const V& b) {
  return {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
}
V mul(const V& a, double s) {
  return {a[0] * s, a[1] * s, a[2] * s};
}
double dot(const V& a, const V& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
V cross(const V& a, const V& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
V unit(const V& a) {
  return mul(a, 1.0 / std::sqrt(dot(a, a)));
}
double degrees(const V& a, const V& b) {
  return std::acos(std::clamp(dot(unit(a), unit(b)), -1.0, 1.0)) * 180.0 / 3.14159265358979;
}

// Everything one LOD's maps need, built the way texture_set.cpp builds it.
struct Baked {
  UvAtlas atlas;
  TexelMap texels;
  TexelHits hits;
  LodBake bake() const { return {&atlas.meshes, &texels, &hits, source}; }
  const AssetMeshes* source = nullptr;
};

Baked prepare(const AssetMeshes& lod, const AssetMeshes& source, const RaySource& rays, int size, double cage) {
  Baked b;
  b.source = &source;
  b.atlas = buildUvAtlas(lod, size, 4);
  computeTangents(b.atlas.meshes.rock);
  computeTangents(b.atlas.meshes.colluvium);
  b.texels = rasterizeUv(b.atlas.meshes, size);
  dilateTexels(b.texels);
  b.hits = traceTexels(b.atlas.meshes, b.texels, rays, cage);
  return b;
}

// A point of the LOD at texel (x, y): weights over its triangle's vertices, by uv.
struct TexelPoint {
  const SurfaceMesh* mesh;
  std::array<std::uint32_t, 3> v;
  std::array<double, 3> w;
  V interpolate(const std::vector<std::array<float, 3>>& a) const {
    V r{0, 0, 0};
    for (int i = 0; i < 3; ++i) r = add(r, mul({a[v[i]][0], a[v[i]][1], a[v[i]][2]}, w[i]));
    return r;
  }
};

TexelPoint texelPoint(const AssetMeshes& m, const TexelMap& texels, int x, int y) {
  const TriangleRef ref = triangleRef(m, texels.texels[std::size_t(y) * texels.size + x]);
  const SurfaceMesh& s = ref.surface == 0 ? m.rock : m.colluvium;
  // Barycentrics by uv, written out here rather than through the baker's texelBarycentrics.
  const auto& t = s.triangles[ref.triangle];
  const double px = (x + 0.5) / texels.size, py = (y + 0.5) / texels.size;
  const auto &a = s.uvs[t[0]], &b = s.uvs[t[1]], &c = s.uvs[t[2]];
  const double d = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
  const double w1 = ((px - a[0]) * (c[1] - a[1]) - (py - a[1]) * (c[0] - a[0])) / d;
  const double w2 = ((b[0] - a[0]) * (py - a[1]) - (b[1] - a[1]) * (px - a[0])) / d;
  return {&s, t, {1 - w1 - w2, w1, w2}};
}

bool covered(const TexelMap& texels, int x, int y) {
  const std::uint32_t t = texels.texels[std::size_t(y) * texels.size + x];
  return t != kEmptyTexel && !(t & kDilatedTexel);
}

// The bumpy sphere r = 1 + a · s(u), s(p) = sin(k x) sin(k y) sin(k z), u the unit direction,
// and its exact normal: the gradient of |p| − 1 − a · s(p / |p|).
constexpr double kBump = 0.05, kWaves = 6.0;
V bumpyNormal(const V& u) {
  const double sx = std::sin(kWaves * u[0]), sy = std::sin(kWaves * u[1]), sz = std::sin(kWaves * u[2]);
  const V grad{kWaves * std::cos(kWaves * u[0]) * sy * sz, kWaves * sx * std::cos(kWaves * u[1]) * sz,
               kWaves * sx * sy * std::cos(kWaves * u[2])};
  const V tangential = add(grad, mul(u, -dot(grad, u)));
  const double r = 1 + kBump * sx * sy * sz;
  return unit(add(u, mul(tangential, -kBump / r)));
}

SurfaceMesh bumpySphere() {
  SurfaceMesh s = test::sphereSurface(6);
  for (auto& p : s.positions) {
    const V u = unit({p[0], p[1], p[2]});
    const double r = 1 + kBump * std::sin(kWaves * u[0]) * std::sin(kWaves * u[1]) * std::sin(kWaves * u[2]);
    p = {float(u[0] * r), float(u[1] * r), float(u[2] * r)};
  }
  return test::surfaceOf(s.positions, s.triangles);
}

TEST(NormalMap, RoundTripDecodedByGltfRules) {
  const AssetMeshes source = test::assetOf(bumpySphere());
  const AssetMeshes lod = test::assetOf(test::sphereSurface(2));
  const RaySource rays(source);
  const int size = 512;
  const Baked b = prepare(lod, source, rays, size, 0.2);
  EXPECT_EQ(b.hits.missed, 0u);
  const TextureImage<std::uint16_t> map = bakeNormalMap(b.bake());
  ASSERT_EQ(map.size, size);
  ASSERT_EQ(map.channels, 3);

  double right = 0, green_flipped = 0, geometry = 0;
  std::size_t n = 0;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      if (!covered(b.texels, x, y)) continue;
      const TexelPoint p = texelPoint(b.atlas.meshes, b.texels, x, y);
      // glTF: interpolate NORMAL, TANGENT.xyz and the bitangent cross(N, T) · w, normalise.
      V normal{0, 0, 0}, tangent{0, 0, 0}, bitangent{0, 0, 0};
      for (int i = 0; i < 3; ++i) {
        const auto& nv = p.mesh->normals[p.v[i]];
        const auto& tv = p.mesh->tangents[p.v[i]];
        const V nn{nv[0], nv[1], nv[2]}, tt{tv[0], tv[1], tv[2]};
        normal = add(normal, mul(nn, p.w[i]));
        tangent = add(tangent, mul(tt, p.w[i]));
        bitangent = add(bitangent, mul(cross(nn, tt), p.w[i] * tv[3]));
      }
      normal = unit(normal), tangent = unit(tangent), bitangent = unit(bitangent);
      const std::uint16_t* texel = &map.pixels[(std::size_t(y) * size + x) * 3];
      const double cx = texel[0] / 65535.0 * 2 - 1, cy = texel[1] / 65535.0 * 2 - 1, cz = texel[2] / 65535.0 * 2 - 1;
      const V decoded = add(add(mul(tangent, cx), mul(bitangent, cy)), mul(normal, cz));
      const V flipped = add(add(mul(tangent, cx), mul(bitangent, -cy)), mul(normal, cz));
      const V truth = bumpyNormal(unit(p.interpolate(p.mesh->positions)));
      right += degrees(decoded, truth);
      green_flipped += degrees(flipped, truth);
      geometry += degrees(normal, truth);
      ++n;
    }
  ASSERT_GT(n, 10000u);
  right /= double(n), green_flipped /= double(n), geometry /= double(n);
  std::printf("mean angle to the bumpy sphere's normal: decoded %.2f°, green flipped %.2f°, geometry alone %.2f°\n",
              right, green_flipped, geometry);
  EXPECT_LT(right, 2.0);
  EXPECT_GT(green_flipped, 3 * right);
  EXPECT_GT(green_flipped, 4.0);
  EXPECT_GT(geometry, 4 * right);
}

TEST(Tangents, FollowUAndMirroredUvFlipsHandedness) {
  // A unit square in z = 0 facing +z; u along +x, v down the image = −y.
  SurfaceMesh m = test::surfaceOf({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 1, 2}, {0, 2, 3}});
  m.uvs = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
  computeTangents(m);
  for (const auto& t : m.tangents) {
    EXPECT_NEAR(t[0], 1.0f, 1e-6);
    EXPECT_NEAR(t[1], 0.0f, 1e-6);
    EXPECT_NEAR(t[2], 0.0f, 1e-6);
    EXPECT_EQ(t[3], 1.0f);  // bitangent cross(+z, +x) = +y: up the image, as v decreases
  }
  for (auto& uv : m.uvs) uv[0] = 1 - uv[0];  // mirrored in u
  computeTangents(m);
  for (const auto& t : m.tangents) {
    EXPECT_NEAR(t[0], -1.0f, 1e-6);
    EXPECT_EQ(t[3], -1.0f);
  }
}

TEST(Rasterize, SharedEdgeClaimedOnce) {
  // Two triangles splitting the whole unit square along a diagonal through texel centres.
  SurfaceMesh m = test::surfaceOf({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {{0, 1, 2}, {0, 2, 3}});
  m.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  const TexelMap t = rasterizeUv(test::assetOf(m), 64);
  EXPECT_EQ(t.covered, 64u * 64u);
  EXPECT_EQ(t.contested, 0u);
  // The same square twice: every texel contested.
  SurfaceMesh twice = m;
  twice.triangles.push_back({0, 1, 2});
  twice.triangles.push_back({0, 2, 3});
  EXPECT_EQ(rasterizeUv(test::assetOf(twice), 64).contested, 64u * 64u);
}

TEST(Occlusion, CreviceDarkerThanConvexTopOpenPlaneNearOne) {
  // Two unit spheres overlapping (centres 1.9 apart): a narrow crevice rings their junction.
  SurfaceMesh pair;
  for (float cx : {-0.95f, 0.95f}) {
    const SurfaceMesh s = test::sphereSurface(4);
    const auto base = std::uint32_t(pair.positions.size());
    for (const auto& p : s.positions) pair.positions.push_back({p[0] + cx, p[1], p[2]});
    for (const auto& t : s.triangles) pair.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  }
  const AssetMeshes spheres = test::assetOf(test::surfaceOf(pair.positions, pair.triangles));
  const RaySource rays(spheres);
  TextureParams params;
  params.ao_rays = 64;
  const int size = 512;
  const Baked b = prepare(spheres, spheres, rays, size, 0.05);
  const auto occlusion = vertexOcclusion(b.atlas.meshes, rays, params, 0);
  const RockLook look(1, rays.radius(), 0.0, {0.0f, 1.0f});
  const TextureImage<std::uint8_t> orm = bakeOrm(b.bake(), occlusion, look);
  // The texels nearest a point in the crevice and the left sphere's outer pole.
  const auto nearest = [&](const V& target) {
    double best = 1e9;
    int value = -1;
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        if (!covered(b.texels, x, y)) continue;
        const V p = texelPoint(b.atlas.meshes, b.texels, x, y).interpolate(b.atlas.meshes.rock.positions);
        const V d = add(p, mul(target, -1));
        if (dot(d, d) < best) best = dot(d, d), value = orm.pixels[(std::size_t(y) * size + x) * 3];
      }
    return value;
  };
  const int crevice = nearest({-0.05, 0.436, 0.0}), top = nearest({-1.95, 0.0, 0.0});
  std::printf("occlusion (R of ORM): crevice %d, convex top %d\n", crevice, top);
  EXPECT_LT(crevice, top - 60);
  EXPECT_GE(top, 235);

  // A flat square open to the sky: nothing occludes it.
  std::vector<std::array<float, 3>> p;
  std::vector<std::array<std::uint32_t, 3>> t;
  for (int j = 0; j <= 10; ++j)
    for (int i = 0; i <= 10; ++i) p.push_back({0.1f * i, 0.1f * j, 0.0f});
  for (int j = 0; j < 10; ++j)
    for (int i = 0; i < 10; ++i) {
      const auto v = std::uint32_t(j * 11 + i);
      t.push_back({v, v + 1, v + 12});
      t.push_back({v, v + 12, v + 11});
    }
  const AssetMeshes plane = test::assetOf(test::surfaceOf(p, t));
  const RaySource plane_rays(plane);
  const Baked pb = prepare(plane, plane, plane_rays, 256, 0.05);
  const auto open = vertexOcclusion(pb.atlas.meshes, plane_rays, params, 0);
  const TextureImage<std::uint8_t> plane_orm = bakeOrm(pb.bake(), open, look);
  for (std::size_t i = 0; i < plane_orm.pixels.size(); i += 3) ASSERT_EQ(plane_orm.pixels[i], 255);
}

TEST(BaseColor, EachLayerShowsItsColourWhereItIs) {
  // The source: a sphere whose upper half is one layer (red-brown) and lower half another
  // (pale buff), as the palette colours vertices; the LOD: a coarse sphere.
  SurfaceMesh fine = test::sphereSurface(5);
  const std::array<float, 3> upper{0.27f, 0.07f, 0.03f}, lower{0.77f, 0.58f, 0.35f};
  for (std::size_t i = 0; i < fine.positions.size(); ++i) {
    const bool up = fine.positions[i][2] > 0;
    fine.colors[i] = up ? upper : lower;
    fine.durability[i] = up ? 3.0f : 0.6f;
  }
  AssetMeshes source = test::assetOf(fine);
  source.durability_range = {0.6f, 3.0f};
  const RaySource rays(source);
  const int size = 512;
  const Baked b = prepare(test::assetOf(test::sphereSurface(2)), source, rays, size, 0.2);
  const RockLook look(7, rays.radius(), 0.05, source.durability_range);
  const TextureImage<std::uint8_t> colour = bakeBaseColor(b.bake(), look);
  std::array<double, 3> sum_up{}, sum_low{};
  std::size_t up = 0, low = 0;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      if (!covered(b.texels, x, y)) continue;
      const V p = texelPoint(b.atlas.meshes, b.texels, x, y).interpolate(b.atlas.meshes.rock.positions);
      if (std::abs(p[2]) < 0.2) continue;  // away from the boundary between the layers
      auto& sum = p[2] > 0 ? sum_up : sum_low;
      (p[2] > 0 ? up : low)++;
      for (int c = 0; c < 3; ++c) sum[c] += srgbToLinear(colour.pixels[(std::size_t(y) * size + x) * 3 + c] / 255.0f);
    }
  ASSERT_GT(up, 1000u);
  ASSERT_GT(low, 1000u);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(sum_up[c] / double(up), upper[c], 0.02) << "channel " << c;
    EXPECT_NEAR(sum_low[c] / double(low), lower[c], 0.03) << "channel " << c;
  }
}

// A PNG's bit depth, colour type and whether it carries an sRGB chunk.
struct PngHeader {
  int depth = 0, colour_type = 0;
  unsigned width = 0;
  bool srgb = false;
};
PngHeader readPngHeader(const std::filesystem::path& file) {
  PngHeader h;
  std::FILE* f = std::fopen(file.c_str(), "rb");
  if (!f) return h;
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  if (!setjmp(png_jmpbuf(png))) {
    png_init_io(png, f);
    png_read_info(png, info);
    h.depth = png_get_bit_depth(png, info);
    h.width = png_get_image_width(png, info);
    h.colour_type = png_get_color_type(png, info);
    h.srgb = png_get_valid(png, info, PNG_INFO_sRGB) != 0;
  }
  png_destroy_read_struct(&png, &info, nullptr);
  std::fclose(f);
  return h;
}

// Every sample of a PNG, as libpng reads it (16-bit in the host's order).
std::vector<std::uint16_t> readPngSamples(const std::filesystem::path& file, int& size, int& channels) {
  std::vector<std::uint16_t> samples;
  std::FILE* f = std::fopen(file.c_str(), "rb");
  if (!f) return samples;
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  if (!setjmp(png_jmpbuf(png))) {
    png_init_io(png, f);
    png_read_png(png, info, PNG_TRANSFORM_SWAP_ENDIAN, nullptr);
    size = int(png_get_image_width(png, info));
    channels = png_get_channels(png, info);
    const int depth = png_get_bit_depth(png, info);
    png_bytepp rows = png_get_rows(png, info);
    for (int y = 0; y < int(png_get_image_height(png, info)); ++y)
      for (int i = 0; i < size * channels; ++i)
        samples.push_back(depth == 16 ? reinterpret_cast<const std::uint16_t*>(rows[y])[i] : rows[y][i]);
  }
  png_destroy_read_struct(&png, &info, nullptr);
  std::fclose(f);
  return samples;
}

TEST(TextureFiles, PngsReadBackSampleForSample) {
  // Noise with structure, so every band compresses differently; 600 rows are 19 bands of 32
  // (the last short) in two IDAT chunks.
  const int size = 600;
  TextureImage<std::uint16_t> normal{size, 3, std::vector<std::uint16_t>(std::size_t(size) * size * 3)};
  TextureImage<std::uint8_t> mask{size, 4, std::vector<std::uint8_t>(std::size_t(size) * size * 4)};
  for (std::size_t i = 0; i < normal.pixels.size(); ++i) normal.pixels[i] = std::uint16_t(i * 2654435761u >> 13);
  for (std::size_t i = 0; i < mask.pixels.size(); ++i) mask.pixels[i] = std::uint8_t((i / 7) ^ (i * 40503u >> 9));
  test::TempDir dir;
  writeTexturePng(dir.path() / "n.png", normal);
  writeTexturePng(dir.path() / "m.png", mask, false);
  int read_size = 0, channels = 0;
  std::vector<std::uint16_t> samples = readPngSamples(dir.path() / "n.png", read_size, channels);
  EXPECT_EQ(read_size, size);
  EXPECT_EQ(channels, 3);
  EXPECT_EQ(samples, normal.pixels);
  samples = readPngSamples(dir.path() / "m.png", read_size, channels);
  EXPECT_EQ(channels, 4);
  ASSERT_EQ(samples.size(), mask.pixels.size());
  for (std::size_t i = 0; i < samples.size(); ++i) ASSERT_EQ(samples[i], mask.pixels[i]) << i;
}

// texture.precision: compact stores the normals in 8 bits within half a degree of the 16-bit ones
// full keeps, and the height in half floats, in steps of 1/256 voxel, within half a step and
// half-float rounding of the 32-bit one;
// directx_normals inverts the green channel and nothing else.
TEST(TextureSet, CompactPrecisionKeepsTheFullMapsWithinRounding) {
  const AssetMeshes& source = test::weatheredRock().meshes;
  const std::vector<AssetMeshes> lods{source};
  test::TempDir compact, full, directx;
  TextureSetRequest request;
  request.params.size = 256;
  request.params.ao_rays = 4;
  request.params.maps = {TextureMap::Normal, TextureMap::Height};
  request.seed = 3;
  request.voxel_size = 2.0 / 32;
  request.name = "p";
  request.folder = compact.path();
  bakeTextureSet(lods, source, request);
  request.folder = directx.path();
  request.directx_normals = true;
  bakeTextureSet(lods, source, request);
  request.folder = full.path();
  request.directx_normals = false;
  request.params.precision = MapPrecision::Full;
  bakeTextureSet(lods, source, request);

  EXPECT_EQ(readPngHeader(compact.path() / "p_Normal_LOD0.png").depth, 8);
  EXPECT_EQ(readPngHeader(full.path() / "p_Normal_LOD0.png").depth, 16);
  int size = 0, channels = 0;
  const std::vector<std::uint16_t> wide = readPngSamples(full.path() / "p_Normal_LOD0.png", size, channels);
  const std::vector<std::uint16_t> narrow = readPngSamples(compact.path() / "p_Normal_LOD0.png", size, channels);
  const std::vector<std::uint16_t> flipped = readPngSamples(directx.path() / "p_Normal_LOD0.png", size, channels);
  ASSERT_EQ(wide.size(), narrow.size());
  ASSERT_EQ(flipped.size(), narrow.size());
  double worst = 0.0, sum = 0.0;
  for (std::size_t i = 0; i + 2 < wide.size(); i += 3) {
    Vec3d a{}, b{};
    for (std::size_t k = 0; k < 3; ++k) a[k] = wide[i + k] / 65535.0 * 2 - 1, b[k] = narrow[i + k] / 255.0 * 2 - 1;
    const double angle = std::acos(std::clamp(dot(normalised(a, a), normalised(b, b)), -1.0, 1.0)) * 180 / M_PI;
    worst = std::max(worst, angle), sum += angle;
    ASSERT_EQ(flipped[i], narrow[i]) << i;
    ASSERT_EQ(flipped[i + 1], 255 - narrow[i + 1]) << i;
    ASSERT_EQ(flipped[i + 2], narrow[i + 2]) << i;
  }
  EXPECT_LT(worst, 0.5);
  EXPECT_GT(sum, 0.0);  // 8 bits do round

  const test::ExrImage half = test::readExr(compact.path() / "p_Height.exr", {"Y"});
  const test::ExrImage whole = test::readExr(full.path() / "p_Height.exr", {"Y"});
  EXPECT_EQ(half.types.at("Y"), Imf::HALF);
  EXPECT_EQ(whole.types.at("Y"), Imf::FLOAT);
  const auto& h = half.plane("Y");
  const auto& f = whole.plane("Y");
  ASSERT_EQ(h.size(), f.size());
  // Rounded to steps of 1/256 of a voxel (a power of two: 2⁻¹² at h = 1/16), then to a half.
  const double step = std::ldexp(1.0, -12);
  std::size_t off_step = 0, finer = 0;
  for (std::size_t i = 0; i < h.size(); ++i) {
    ASSERT_NEAR(h[i], f[i], step / 2 + std::abs(f[i]) / 1024 + 1e-7) << i;  // a half keeps 11 significant bits
    off_step += std::abs(h[i]) < 0.5 && std::fmod(double(h[i]), step) != 0.0;
    finer += std::fmod(double(f[i]), step) != 0.0;
  }
  EXPECT_EQ(off_step, 0u);
  EXPECT_GT(finer, h.size() / 2);  // the float map has finer detail: the step did round
}

TEST(TextureSet, FilesByteIdenticalAtOneAndTwoThreads) {
  const AssetMeshes& source = test::weatheredRock().meshes;
  std::vector<AssetMeshes> lods{source};
  lods.push_back(simplifyLods(source, {{0.2}}).front());
  test::TempDir one, two;
  TextureSetRequest request;
  request.params.size = 512;
  request.params.lod_size = LodMapSize::Full;
  request.params.ao_rays = 8;
  request.seed = 3;
  request.voxel_size = 2.0 / 32;
  request.name = "small";
  TextureSet sets[2];
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    request.folder = one.path();
    sets[0] = bakeTextureSet(lods, source, request);
  }
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
    request.folder = two.path();
    sets[1] = bakeTextureSet(lods, source, request);
  }
  // LOD0: five maps and the History map (goblin has a look); LOD1: all but the height.
  ASSERT_EQ(sets[0].files.size(), 11u);
  for (const TextureFile& f : sets[0].files) {
    EXPECT_EQ(test::readBytes(one.path() / f.file), test::readBytes(two.path() / f.file)) << f.file;
  }
  EXPECT_TRUE(std::filesystem::exists(one.path() / "small_BaseColor.png"));
  EXPECT_TRUE(std::filesystem::exists(one.path() / "small_Normal_LOD0.png"));
  EXPECT_TRUE(std::filesystem::exists(one.path() / "small_Normal_LOD1.png"));
  EXPECT_TRUE(std::filesystem::exists(one.path() / "small_BaseColor_LOD1.png"));
  EXPECT_FALSE(std::filesystem::exists(one.path() / "small_Height_LOD1.exr"));

  const PngHeader colour = readPngHeader(one.path() / "small_BaseColor.png");
  EXPECT_EQ(colour.depth, 8);
  EXPECT_EQ(colour.colour_type, PNG_COLOR_TYPE_RGB);
  EXPECT_TRUE(colour.srgb);
  const PngHeader normal = readPngHeader(one.path() / "small_Normal_LOD0.png");
  EXPECT_EQ(normal.depth, 8);  // texture.precision: compact, the default
  EXPECT_FALSE(normal.srgb);
  const PngHeader mask = readPngHeader(one.path() / "small_Mask.png");
  EXPECT_EQ(mask.colour_type, PNG_COLOR_TYPE_RGB_ALPHA);
  EXPECT_FALSE(mask.srgb);

  // The height: one float channel, the LOD0-to-source distance, within the cage.
  const test::ExrImage height = test::readExr(one.path() / "small_Height.exr", {"Y"});  // throws without a Y
  EXPECT_EQ(height.types.at("Y"), Imf::HALF);
  ASSERT_EQ(height.width, 512);
  ASSERT_EQ(height.height, 512);
  // LOD0 is its own source here: every distance is zero but for float rounding (a ray that
  // runs nearly along its triangle, at a rim, meets it a little way off).
  for (float h : height.plane("Y")) ASSERT_LT(std::abs(h), 1e-3f);
}

// A map made in bands of rows (the hero's memory bound, docs/textures.md "Memory") is the
// whole map byte for byte, whatever the band height: one that divides neither the map, nor
// the PNG encoder's 512-row groups, nor the EXR's 16-line blocks; a single row; one as high
// as the map. LOD1 is simplified, so its empty texels copy texels in other bands.
TEST(TextureSet, BandedMapsEqualWholeMapsAtAnyBandHeight) {
  const AssetMeshes& source = test::weatheredRock().meshes;
  std::vector<AssetMeshes> lods{source};
  lods.push_back(simplifyLods(source, {{0.2}}).front());
  TextureSetRequest request;
  request.params.ao_rays = 8;
  request.seed = 5;
  request.voxel_size = 2.0 / 32;
  request.name = "banded";
  // At 1024 the PNG encoder's 512-row groups lie in one band of 512 (read in place) or
  // straddle bands of 700 (copied together).
  const std::vector<std::pair<int, std::vector<int>>> cases{{512, {37, 1, 100, 512}}, {1024, {512, 700}}};
  for (const auto& [size, heights] : cases) {
    request.params.size = size;
    request.whole_map_size = 2048;
    request.band_rows = 0;
    test::TempDir whole;
    request.folder = whole.path();
    const TextureSet reference = bakeTextureSet(lods, source, request);
    ASSERT_EQ(reference.files.size(), 11u);  // LOD0: five maps and the look's History; LOD1: all but the height
    for (int rows : heights) {
      test::TempDir banded;
      request.folder = banded.path();
      request.whole_map_size = 0;  // every map in bands
      request.band_rows = rows;
      const TextureSet set = bakeTextureSet(lods, source, request);
      ASSERT_EQ(set.files.size(), reference.files.size());
      for (const TextureFile& f : reference.files)
        EXPECT_EQ(test::readBytes(banded.path() / f.file), test::readBytes(whole.path() / f.file))
            << f.file << " at " << size << " in bands of " << rows << " rows";
    }
  }
}

// A surface seen from its back is passed through (ray_source.h): a LOD point between an
// overhang's underside just above it (facing down, away from the LOD's up normal) and the rock
// surface further below (facing up) takes the surface below, one ray at a time and in a packet.
TEST(RaySource, PassesThroughASurfaceSeenFromItsBack) {
  AssetMeshes source;
  SurfaceMesh& m = source.rock;
  m.name = "rock";
  const auto quad = [&m](float z, float nz) {
    const auto base = std::uint32_t(m.positions.size());
    for (const auto& xy : {std::array<float, 2>{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}) {
      m.positions.push_back({xy[0], xy[1], z});
      m.normals.push_back({0, 0, nz});
    }
    if (nz > 0)
      m.triangles.insert(m.triangles.end(), {{base, base + 1, base + 2}, {base, base + 2, base + 3}});
    else
      m.triangles.insert(m.triangles.end(), {{base, base + 2, base + 1}, {base, base + 3, base + 2}});
  };
  quad(0.01f, -1.0f);  // the underside of an overhang, 0.01 above the LOD point
  quad(-0.03f, 1.0f);  // the rock surface, 0.03 below it
  const RaySource rays(source);
  const std::array<float, 3> origin{0.1f, 0.2f, 0.0f}, up{0, 0, 1};
  const SourceHit one = rays.nearestAlong(0, origin, up, 0.5f);
  ASSERT_TRUE(one.hit);
  EXPECT_NEAR(one.distance, -0.03f, 1e-4f);  // the nearer hit ahead faces away from the LOD
  EXPECT_GE(one.triangle, 2u);

  const int surface[RaySource::kPacket] = {0, 0, 0};
  const std::array<float, 3> origins[RaySource::kPacket] = {origin, {-0.4f, 0.3f, 0.0f}, {0.2f, 0.1f, -0.2f}};
  const std::array<float, 3> directions[RaySource::kPacket] = {up, up, {0, 0, -1}};
  SourceHit packet[RaySource::kPacket];
  rays.nearestAlong(3, surface, origins, directions, 0.5f, packet);
  ASSERT_TRUE(packet[0].hit && packet[1].hit);
  EXPECT_NEAR(packet[0].distance, -0.03f, 1e-4f);
  EXPECT_NEAR(packet[1].distance, -0.03f, 1e-4f);
  // Asked for a surface facing down from below both: the rock surface's back is passed through
  // to the overhang's underside.
  ASSERT_TRUE(packet[2].hit);
  EXPECT_NEAR(packet[2].distance, -0.21f, 1e-4f);
  EXPECT_LT(packet[2].triangle, 2u);
}

// Any texel's hit is found without a scan of its row, in every block of the row.
TEST(TraceTexels, HitIndexCountsTheCoveredTexelsBeforeTheTexel) {
  const AssetMeshes& source = test::weatheredRock().meshes;
  UvAtlas atlas = buildUvAtlas(source, 300, 4);
  TexelMap texels = rasterizeUv(atlas.meshes, 300);
  dilateTexels(texels);
  RaySource rays(source);
  const TexelHits hits = traceTexels(atlas.meshes, texels, rays, 0.1 * rays.radius());
  std::size_t k = 0;
  for (int y = 0; y < 300; ++y)
    for (int x = 0; x < 300; ++x) {
      const std::uint32_t t = texels.texels[std::size_t(y) * 300 + std::size_t(x)];
      if (t == kEmptyTexel || (t & kDilatedTexel)) continue;
      ASSERT_EQ(hitIndex(texels, hits, x, y), k++) << x << ", " << y;
    }
  EXPECT_EQ(k, hits.hits.size());
}

TEST(TextureSet, HalvedSizesNameEveryLodsMapsAndRefuseBadParams) {
  const AssetMeshes sphere = test::assetOf(test::sphereSurface(3));
  test::TempDir dir;
  TextureSetRequest request;
  request.params.size = 512;
  request.params.ao_rays = 4;
  request.params.maps = {TextureMap::BaseColor, TextureMap::Normal, TextureMap::Orm};
  request.name = "s";
  request.folder = dir.path() / "textures";
  // LOD0 at 512, LOD1 at 256, LOD2 at 256 (the floor), each with its own atlas and files.
  const TextureSet set = bakeTextureSet({sphere, sphere, sphere}, sphere, request);
  std::vector<std::string> files;
  for (const TextureFile& f : set.files) files.push_back(f.file + "@" + std::to_string(f.size));
  EXPECT_EQ(files,
            (std::vector<std::string>{"s_BaseColor.png@512", "s_Normal_LOD0.png@512", "s_ORM.png@512",
                                      "s_BaseColor_LOD1.png@256", "s_Normal_LOD1.png@256", "s_ORM_LOD1.png@256",
                                      "s_BaseColor_LOD2.png@256", "s_Normal_LOD2.png@256", "s_ORM_LOD2.png@256"}));
  EXPECT_EQ(set.sizes, (std::vector<int>{512, 256, 256}));
  EXPECT_EQ(readPngHeader(dir.path() / "textures" / "s_ORM_LOD1.png").width, 256u);
  // The same LOD at half the map size: about half the texels per world unit (the gutters keep
  // their width in texels, and how well a few charts pack varies with the map's size).
  EXPECT_NEAR(set.texels_per_unit[1] / set.texels_per_unit[0], 0.5, 0.1);
  ASSERT_NE(findTextureFile(set, 2, TextureMap::Orm), nullptr);
  EXPECT_EQ(findTextureFile(set, 2, TextureMap::Orm)->file, "s_ORM_LOD2.png");
  EXPECT_EQ(findTextureFile(set, 0, TextureMap::Height), nullptr);
  request.params.size = 3000;
  EXPECT_THROW(bakeTextureSet({sphere}, sphere, request), std::invalid_argument);
}

TEST(TextureSet, LodMapSizes) {
  TextureParams p;
  p.size = 2048;
  EXPECT_EQ(lodMapSize(p, 0), 2048);
  EXPECT_EQ(lodMapSize(p, 1), 1024);
  EXPECT_EQ(lodMapSize(p, 3), 256);
  EXPECT_EQ(lodMapSize(p, 4), 256);
  p.size = 256;
  EXPECT_EQ(lodMapSize(p, 2), 256);
  p.lod_size = LodMapSize::Full;
  p.size = 1024;
  EXPECT_EQ(lodMapSize(p, 4), 1024);
}

TEST(TextureSet, ColourMapSizes) {
  TextureParams p;
  EXPECT_EQ(p.colour_density, 3.0);
  EXPECT_EQ(colourMapSize(p, 2048, 7.2), 1024);  // goblin's LOD0: 3.6 texels a voxel kept
  EXPECT_EQ(colourMapSize(p, 1024, 3.5), 1024);  // its LOD1: a half would keep 1.75
  EXPECT_EQ(colourMapSize(p, 2048, 24.0), 256);  // halved three times, to exactly 3 a voxel
  EXPECT_EQ(colourMapSize(p, 512, 100.0), 256);  // never below 256
  EXPECT_EQ(colourMapSize(p, 128, 100.0), 128);  // nor below a smaller LOD's own size
  EXPECT_EQ(colourMapSize(p, 2048, 0.0), 2048);  // no voxel size: no scale to keep
  p.colour_density = 0;
  EXPECT_EQ(colourMapSize(p, 2048, 7.2), 2048);
  EXPECT_TRUE(isColourMap(TextureMap::BaseColor) && isColourMap(TextureMap::Orm) && isColourMap(TextureMap::Mask) &&
              isColourMap(TextureMap::History));
  EXPECT_FALSE(isColourMap(TextureMap::Normal) || isColourMap(TextureMap::Height));
}

// Sample (channel `c` of `channels`) of a square map at uv, bilinearly with clamped edges, as
// glTF's linear filter reads it.
double bilinear(const std::vector<std::uint16_t>& map, int size, int channels, int c, double u, double v) {
  const double x = u * size - 0.5, y = v * size - 0.5;
  const int x0 = int(std::floor(x)), y0 = int(std::floor(y));
  const double tx = x - x0, ty = y - y0;
  const auto at = [&](int xi, int yi) {
    xi = std::clamp(xi, 0, size - 1), yi = std::clamp(yi, 0, size - 1);
    return double(
        map[(std::size_t(yi) * std::size_t(size) + std::size_t(xi)) * std::size_t(channels) + std::size_t(c)]);
  };
  return (1 - ty) * ((1 - tx) * at(x0, y0) + tx * at(x0 + 1, y0)) +
         ty * ((1 - tx) * at(x0, y0 + 1) + tx * at(x0 + 1, y0 + 1));
}

TEST(TextureSet, ColourMapsAtTheirOwnSizeReadAsTheFullSizeOnes) {
  const AssetMeshes& source = test::weatheredRock().meshes;
  test::TempDir full, halved;
  TextureSetRequest request;
  request.params.size = 512;
  request.params.ao_rays = 4;
  request.params.maps = {TextureMap::BaseColor, TextureMap::Normal, TextureMap::Orm, TextureMap::Height,
                         TextureMap::Mask};
  request.params.colour_density = 0;
  request.seed = 3;
  request.voxel_size = 2.0 / 32;
  request.name = "c";
  request.folder = full.path();
  const TextureSet whole = bakeTextureSet({source}, source, request);
  // A density one halving keeps and a second does not.
  const double texels_per_voxel = whole.texels_per_unit[0] * request.voxel_size;
  request.params.colour_density = 0.45 * texels_per_voxel;
  request.folder = halved.path();
  const TextureSet set = bakeTextureSet({source}, source, request);

  std::vector<std::string> files;
  for (const TextureFile& f : set.files) files.push_back(f.file + "@" + std::to_string(f.size));
  EXPECT_EQ(files, (std::vector<std::string>{"c_BaseColor.png@256", "c_Normal_LOD0.png@512", "c_ORM.png@256",
                                             "c_Height.exr@512", "c_Mask.png@256", "c_History.png@256"}));
  EXPECT_EQ(set.sizes, (std::vector<int>{512}));
  EXPECT_EQ(readPngHeader(halved.path() / "c_BaseColor.png").width, 256u);
  // The relief maps are the same bytes as at density 0.
  EXPECT_EQ(test::readBytes(halved.path() / "c_Normal_LOD0.png"), test::readBytes(full.path() / "c_Normal_LOD0.png"));
  {
    // A set of colour maps alone is at their size, and its texels traced once.
    test::TempDir alone;
    TextureSetRequest colour_only = request;
    colour_only.params.maps = {TextureMap::BaseColor};
    colour_only.folder = alone.path();
    const TextureSet only = bakeTextureSet({source}, source, colour_only);
    EXPECT_EQ(only.sizes, (std::vector<int>{256}));
    ASSERT_EQ(only.files.size(), 2u);  // and the look's History map
    EXPECT_EQ(only.files[0].size, 256);
    EXPECT_EQ(test::readBytes(alone.path() / "c_BaseColor.png"), test::readBytes(halved.path() / "c_BaseColor.png"));
    EXPECT_EQ(only.steps.all().end(), std::find_if(only.steps.all().begin(), only.steps.all().end(),
                                                   [](const PhaseTime& t) { return t.name == "lod0 rays"; }));
  }

  // On the texels the uvs cover, each half-size map sampled where a renderer samples it (at the
  // full map's texel centres) against the full-size map: within a few 8-bit steps on average,
  // against a spread of values many times larger.
  const TexelMap covered = rasterizeUv(set.lods[0], 512);
  for (const char* map : {"c_BaseColor.png", "c_ORM.png", "c_Mask.png", "c_History.png"}) {
    int big = 0, small = 0, channels = 0, small_channels = 0;
    const std::vector<std::uint16_t> a = readPngSamples(full.path() / map, big, channels);
    const std::vector<std::uint16_t> b = readPngSamples(halved.path() / map, small, small_channels);
    ASSERT_EQ(big, 512) << map;
    ASSERT_EQ(small, 256) << map;
    ASSERT_EQ(channels, small_channels) << map;
    double diff = 0, sum = 0, sum2 = 0;
    std::size_t n = 0;
    for (int y = 0; y < big; ++y)
      for (int x = 0; x < big; ++x) {
        const std::size_t i = std::size_t(y) * std::size_t(big) + std::size_t(x);
        if (covered.texels[i] == kEmptyTexel) continue;
        for (int c = 0; c < channels; ++c) {
          const double full_value = a[i * std::size_t(channels) + std::size_t(c)] / 255.0;
          diff += std::abs(bilinear(b, small, channels, c, (x + 0.5) / big, (y + 0.5) / big) / 255.0 - full_value);
          sum += full_value, sum2 += full_value * full_value, ++n;
        }
      }
    ASSERT_GT(n, 10000u) << map;
    const double mean_diff = diff / double(n);
    const double spread = std::sqrt(std::max(0.0, sum2 / double(n) - (sum / double(n)) * (sum / double(n))));
    EXPECT_LT(mean_diff, 0.012) << map;
    EXPECT_GT(spread, 5 * mean_diff) << map;
  }
}

TEST(Dilate, EveryEmptyTexelCopiesTheNearestCoveredOne) {
  // Two small squares far apart in a 64² map: every texel ends up pointing at a covered texel
  // of the square nearer to it.
  SurfaceMesh m =
      test::surfaceOf({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 0}, {3, 0, 0}, {3, 1, 0}, {2, 1, 0}},
                      {{0, 1, 2}, {0, 2, 3}, {4, 5, 6}, {4, 6, 7}});
  m.uvs = {{0.1f, 0.1f}, {0.2f, 0.1f}, {0.2f, 0.2f}, {0.1f, 0.2f},
           {0.8f, 0.8f}, {0.9f, 0.8f}, {0.9f, 0.9f}, {0.8f, 0.9f}};
  TexelMap t = rasterizeUv(test::assetOf(m), 64);
  const std::vector<std::uint32_t> covered = t.texels;
  dilateTexels(t);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      const std::size_t i = std::size_t(y) * 64 + x, from = valueTexel(t, i);
      ASSERT_NE(covered[from], kEmptyTexel);
      const bool first_square = covered[from] < 2, nearer_first = x + y < 63;  // either side of the diagonal
      if (std::abs(x + y - 63) > 2) {
        EXPECT_EQ(first_square, nearer_first) << x << "," << y;
      }
      if (covered[i] != kEmptyTexel) {
        EXPECT_EQ(from, i);
      }
    }
}

}  // namespace
}  // namespace rockbake

namespace rockbake {
namespace {

// The mask's alpha (bake_maps.h, GroundMask): 1 where a box standing on the ground meets it,
// fading to 0 three voxels away, and 0 everywhere for an asset off the ground.
TEST(BakeMaps, TheGroundContactFadesOverThreeVoxels) {
  // A unit box on z = 0, counter-clockwise seen from outside, its floor the ground cap.
  std::vector<std::array<float, 3>> p;
  for (int i = 0; i < 8; ++i) p.push_back({float(i & 1), float((i >> 1) & 1), float((i >> 2) & 1)});
  const std::vector<std::array<std::uint32_t, 3>> t = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6},
                                                       {0, 1, 4}, {1, 5, 4}, {2, 6, 3}, {3, 6, 7},
                                                       {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  AssetMeshes box = test::assetOf(test::surfaceOf(std::move(p), t));
  box.bounds_min = {0, 0, 0}, box.bounds_max = {1, 1, 1};
  const double voxel = 0.05;
  const GroundMask mask = groundMask(box, 0.0, voxel);
  ASSERT_TRUE(mask.contact);
  // Within the distance grid's half-voxel cells of the exact smoothstep: 1 on the foot of a side,
  // 1 - (1/9)(3 - 2/3) a voxel up.
  EXPECT_NEAR(mask.at({1.0, 0.5, 0.0}), 1.0, 0.05);
  EXPECT_NEAR(mask.at({1.0, 0.5, voxel}), 1.0 - (3.0 - 2.0 / 3.0) / 9.0, 0.05);
  EXPECT_EQ(mask.at({1.0, 0.5, 3.01 * voxel}), 0.0);           // three voxels up
  EXPECT_EQ(mask.at({0.5, 0.5, 1.0}), 0.0);                    // the top
  EXPECT_FALSE(groundMask(box, std::nullopt, voxel).contact);  // off the ground: no contact
  EXPECT_EQ(groundMask(box, std::nullopt, voxel).at({1.0, 0.5, 0.0}), 0.0);
}

}  // namespace
}  // namespace rockbake
