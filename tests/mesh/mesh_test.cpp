// Meshes (docs/meshes.md): extraction, subdivision, attributes and palettes,
// PLY/OBJ/GLB exports read back, LODs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>

#include <tiny_gltf.h>
#include <nlohmann/json.hpp>

#include "export/glb_file.h"
#include "export/obj_file.h"
#include "export/ply_file.h"
#include "geometry/mesh_checks.h"
#include "geometry/triangle_geometry.h"
#include "mesh/bake_attributes.h"
#include "mesh/extract_surfaces.h"
#include "mesh/simplify_lods.h"
#include "mesh/subdivide.h"
#include "pipeline/bake_asset.h"
#include "pipeline/bake_meshes.h"
#include "pipeline/export_meshes.h"
#include "platform/colour.h"
#include "platform/stopwatch.h"
#include "sim/shapes.h"
#include "sim/weathering.h"
#include "test_support.h"

namespace rockbake {
namespace {

// ---- fixtures: small weathered rocks, built once ----

// Paper Fig. 9 at 32³: a free-floating cube weathered to half its volume, a sphere.
const VoxelRock& weatheredSphere() {
  static const VoxelRock rock = [] {
    Preset p = test::cubePreset(3.2, 32, 0.4);
    p.response = {ResponseParams::Kind::Threshold, 0.5, {}};
    p.stop.cycles = 1000;
    p.stop.rock_volume_fraction = 0.5;
    return weatherRock(buildInitialRock(resolveShape(p), p), p).rock;
  }();
  return rock;
}

// A box on the ground with a durable band at altitudes 0.45..0.65, rockfall
// and colluvium on: both surfaces, a ground contact, and a band to colour.
Preset bandedPreset() {
  Preset p = test::cubePreset(3.0, 30, 0.3);
  p.grid.size = {4.0, 4.0, 3.0};
  p.grid.resolution = 40;
  p.grid.ground = true;
  p.shape.kind = BoxShape{{2.4, 2.4, 2.7}};
  p.shape.center.reset();
  p.durability.graph.points = {{0.0, 1.0}, {0.4, 1.0}, {0.45, 3.0}, {0.65, 3.0}, {0.7, 1.0}, {1.0, 1.0}};
  p.response = {ResponseParams::Kind::Power, 1.0, {}};
  p.rockfall.mode = RockfallMode::Drop;
  p.colluvium.yield = 0.5;
  p.stop.cycles = 8;
  p.bake.palette = Palette::Debug;
  return p;
}

const VoxelRock& bandedRock() {
  static const VoxelRock rock = [] {
    const Preset p = bandedPreset();
    return weatherRock(buildInitialRock(resolveShape(p), p), p).rock;
  }();
  return rock;
}

AssetMeshes attributed(const VoxelRock& rock, const Preset& p, int levels) {
  AssetMeshes m = extractSurfaces(rock, {p.mesh.smoothing});
  const std::vector<float> exposure = exposureField(rock, p.bubbles);
  m = sampleAttributes(std::move(m), {&rock, &exposure});
  m.rock = subdivideSurface(m.rock, {levels});
  m.colluvium = subdivideSurface(m.colluvium, {levels});
  return applyPalette(std::move(m), paletteParams(rock, p.bake));
}

const AssetMeshes& bandedMeshes(int levels) {
  static std::map<int, AssetMeshes> cache;
  auto it = cache.find(levels);
  if (it == cache.end()) it = cache.emplace(levels, attributed(bandedRock(), bandedPreset(), levels)).first;
  return it->second;
}

Preset spherePreset() {
  Preset p = test::cubePreset(3.2, 32, 0.4);
  p.response = {ResponseParams::Kind::Threshold, 0.5, {}};
  return p;
}

// ---- measurements ----

using Faces = std::vector<std::array<std::uint32_t, 3>>;

// Every undirected edge in exactly two faces, every directed edge in one
// (so neighbouring faces agree on orientation). Returns the edge count.
std::size_t expectClosedManifold(const SurfaceMesh& m) {
  const std::vector<OpenEdge> open = findOpenEdges(m);
  EXPECT_TRUE(open.empty()) << m.name << ": " << open.size()
                            << " edges not shared by exactly two consistently oriented faces";
  return (3 * m.triangles.size() + 4 * m.quads.size()) / 2;  // edges of a closed 2-manifold
}

double triangleArea(const SurfaceMesh& m, const std::array<std::uint32_t, 3>& t) {
  return rockbake::triangleArea(m.positions[t[0]], m.positions[t[1]], m.positions[t[2]]);
}

void expectNoDegenerateFaces(const SurfaceMesh& m, double min_area) {
  std::size_t bad = 0;
  for (const auto& t : m.triangles)
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2] || triangleArea(m, t) <= min_area) ++bad;
  EXPECT_EQ(bad, 0u) << m.name << ": degenerate triangles";
}

double voxelVolume(const VoxelRock& rock, Material m) {
  return double(rock.count(m)) * rock.layout.h * rock.layout.h * rock.layout.h;
}

// Checks every exported mesh must pass; returns the Euler characteristic.
long expectWatertight(const SurfaceMesh& m, double h) {
  const std::size_t edges = expectClosedManifold(m);
  expectNoDegenerateFaces(m, 1e-6 * h * h);
  EXPECT_GT(signedVolume(m), 0.0) << m.name;
  return long(m.positions.size()) - long(edges) + long(m.triangles.size() + m.quads.size());
}

// ---- extraction ----

TEST(MeshExtract, SphereIsClosedOutwardGenusZero) {
  const VoxelRock& rock = weatheredSphere();
  const AssetMeshes m = extractSurfaces(rock, {1.0});
  ASSERT_FALSE(m.rock.positions.empty());
  EXPECT_TRUE(m.colluvium.positions.empty());
  EXPECT_FALSE(m.rock.quads.empty()) << "quad-dominant";
  EXPECT_EQ(expectWatertight(m.rock, rock.layout.h), 2);
}

TEST(MeshExtract, VolumeMatchesVoxelsAtLevelsZeroAndTwo) {
  const VoxelRock& rock = weatheredSphere();
  const double voxels = voxelVolume(rock, Material::Rock);
  const AssetMeshes m = extractSurfaces(rock, {1.0});
  for (int levels : {0, 2}) {
    SurfaceMesh s = subdivideSurface(m.rock, {levels});
    EXPECT_NEAR(signedVolume(s) / voxels, 1.0, 0.05) << "level " << levels;
    EXPECT_EQ(expectWatertight(s, rock.layout.h), 2) << "level " << levels;
  }
}

TEST(MeshExtract, GroundedRockAndColluviumCloseOnTheGround) {
  const VoxelRock& rock = bandedRock();
  ASSERT_GT(rock.count(Material::Colluvium), 0u);
  const AssetMeshes m = extractSurfaces(rock, {1.0});
  ASSERT_FALSE(m.colluvium.positions.empty());
  for (const SurfaceMesh* s : {&m.rock, &m.colluvium}) {
    expectWatertight(*s, rock.layout.h);
    float lowest = 1e30f;
    for (const auto& p : s->positions) lowest = std::min(lowest, p[2]);
    EXPECT_EQ(lowest, 0.0f) << s->name << " rests on z = 0";
  }
  // A sharp-edged box loses a little more to smoothing than a weathered rock
  // does; unsmoothed, the cap on the ground adds no volume error of its own.
  EXPECT_NEAR(signedVolume(m.rock) / voxelVolume(rock, Material::Rock), 1.0, 0.06);
  EXPECT_NEAR(signedVolume(extractSurfaces(rock, {0.0}).rock) / voxelVolume(rock, Material::Rock), 1.0, 0.02);
  // Level 2: still closed, still on (never below) the ground, and the cap on
  // the ground keeps its area (its rim is a sharp crease, not rounded off).
  const auto groundArea = [](const SurfaceMesh& s) {
    double area = 0;
    for (const auto& t : s.triangles)
      if (s.positions[t[0]][2] == 0.0f && s.positions[t[1]][2] == 0.0f && s.positions[t[2]][2] == 0.0f)
        area += triangleArea(s, t);
    for (const auto& q : s.quads)
      if (s.positions[q[0]][2] == 0.0f && s.positions[q[1]][2] == 0.0f && s.positions[q[2]][2] == 0.0f &&
          s.positions[q[3]][2] == 0.0f)
        area += triangleArea(s, {q[0], q[1], q[2]}) + triangleArea(s, {q[0], q[2], q[3]});
    return area;
  };
  const AssetMeshes& sub = bandedMeshes(2);
  for (const SurfaceMesh* s : {&sub.rock, &sub.colluvium}) {
    expectWatertight(*s, rock.layout.h);
    for (const auto& p : s->positions) ASSERT_GE(p[2], 0.0f);
  }
  const double cap0 = groundArea(m.rock), cap2 = groundArea(sub.rock);
  EXPECT_GT(cap0, 0.0);
  EXPECT_NEAR(cap2 / cap0, 1.0, 0.05);
}

TEST(MeshExtract, SmoothingZeroAndFourStayClosed) {
  const VoxelRock& rock = weatheredSphere();
  for (double smoothing : {0.0, 4.0}) {
    const AssetMeshes m = extractSurfaces(rock, {smoothing});
    EXPECT_EQ(expectWatertight(m.rock, rock.layout.h), 2) << "smoothing " << smoothing;
  }
}

// ---- subdivision and attributes ----

TEST(MeshSubdivide, VertexCountFollowsCatmullClark) {
  const VoxelRock& rock = weatheredSphere();
  const AssetMeshes m = extractSurfaces(rock, {1.0});
  const std::size_t edges = expectClosedManifold(m.rock);
  for (int levels : {1, 2, 3}) {
    const SurfaceMesh s = subdivideSurface(m.rock, {levels});
    std::size_t expected_v = m.rock.positions.size(), expected_e = edges,
                expected_f = m.rock.triangles.size() + m.rock.quads.size(),
                corners = 3 * m.rock.triangles.size() + 4 * m.rock.quads.size();
    for (int l = 0; l < levels; ++l) {  // V' = V + E + F, E' = 2E + corners, F' = corners
      expected_v += expected_e + expected_f;
      expected_e = 2 * expected_e + corners;
      expected_f = corners;
      corners = 4 * expected_f;
    }
    EXPECT_EQ(s.positions.size(), expected_v) << "level " << levels;
    EXPECT_EQ(s.positions.size(),
              catmullClarkVertexCount(m.rock.positions.size(), m.rock.triangles.size(), m.rock.quads.size(), levels));
    EXPECT_EQ(s.triangles.size(), 2 * expected_f) << "level " << levels;
    EXPECT_TRUE(s.quads.empty());
    EXPECT_EQ(s.normals.size(), s.positions.size());
  }
  EXPECT_THROW(subdivideSurface(m.rock, {4}), std::invalid_argument);
}

TEST(MeshAttributes, RefinedValuesStayWithinTheInputRange) {
  const Preset p = bandedPreset();
  const VoxelRock& rock = bandedRock();
  AssetMeshes m = extractSurfaces(rock, {1.0});
  const std::vector<float> exposure = exposureField(rock, p.bubbles);
  m = sampleAttributes(std::move(m), {&rock, &exposure});
  const auto range = [](const std::vector<float>& v) {
    return std::pair{*std::min_element(v.begin(), v.end()), *std::max_element(v.begin(), v.end())};
  };
  const PaletteParams palette = paletteParams(rock, VertexPaletteParams{Palette::Debug, {}, {}});
  for (const SurfaceMesh* base : {&m.rock, &m.colluvium}) {
    ASSERT_EQ(base->durability.size(), base->positions.size());
    const SurfaceMesh s = subdivideSurface(*base, {2});
    const std::vector<const std::vector<float>*> in{&base->durability, &base->colluvium, &base->curvature,
                                                    &base->altitude};
    const std::vector<const std::vector<float>*> out{&s.durability, &s.colluvium, &s.curvature, &s.altitude};
    for (std::size_t a = 0; a < in.size(); ++a) {
      const auto [lo, hi] = range(*in[a]);
      const auto [rlo, rhi] = range(*out[a]);
      EXPECT_GE(rlo, lo - 1e-5f) << base->name << " attribute " << a;
      EXPECT_LE(rhi, hi + 1e-5f) << base->name << " attribute " << a;
      EXPECT_GE(lo, 0.0f);
    }
    const auto [clo, chi] = range(base->colluvium);
    const auto [slo, shi] = range(base->curvature);
    const auto [alo, ahi] = range(base->altitude);
    EXPECT_LE(chi, 1.0f);
    EXPECT_LE(shi, 1.0f);
    EXPECT_LE(ahi, 1.0f);
    (void)clo, (void)slo, (void)alo;
  }
  const auto [dlo, dhi] = range(m.rock.durability);
  EXPECT_GE(dlo, palette.durability_min - 1e-5f);
  EXPECT_LE(dhi, palette.durability_max + 1e-5f);
  EXPECT_EQ(range(m.colluvium.colluvium).first, 1.0f);
}

TEST(MeshAttributes, DurableBandStaysRedInDebug) {
  const AssetMeshes& m = bandedMeshes(2);
  // Rock surface vertices well inside the durable band (altitude 0.45..0.65),
  // and well inside the soft rock above and below it, not touching colluvium.
  std::size_t band = 0, red = 0, soft = 0, blue = 0;
  for (std::size_t i = 0; i < m.rock.positions.size(); ++i) {
    const auto& c = m.rock.colors[i];
    const float a = m.rock.altitude[i];
    if (m.rock.colluvium[i] > 0.0f) continue;
    if (a > 0.5f && a < 0.6f) {
      ++band;
      red += c[0] > 0.9f && c[1] < 0.1f && c[2] < 0.1f;
    } else if ((a > 0.25f && a < 0.38f) || (a > 0.72f && a < 0.8f)) {
      ++soft;
      blue += c[2] > 0.9f && c[0] < 0.1f;
    }
  }
  ASSERT_GT(band, 100u);
  EXPECT_GE(double(red) / double(band), 0.95);
  ASSERT_GT(soft, 10u);
  EXPECT_GE(double(blue) / double(soft), 0.95);
  // Colluvium is purple in debug.
  for (const auto& c : m.colluvium.colors) {
    ASSERT_NEAR(c[0], 0.5f, 1e-5f);
    ASSERT_NEAR(c[2], 0.5f, 1e-5f);
  }
}

TEST(MeshAttributes, CurvaturePaletteRedConvexBlueConcave) {
  const Preset p = spherePreset();
  const AssetMeshes m = attributed(
      weatheredSphere(),
      [&] {
        Preset q = p;
        q.bake.palette = Palette::Curvature;
        return q;
      }(),
      1);
  for (std::size_t i = 0; i < m.rock.positions.size(); ++i) {
    const auto& c = m.rock.colors[i];
    const float s = m.rock.curvature[i];
    if (s > 0.55f) {
      ASSERT_GT(c[0], c[2]);
    } else if (s < 0.45f) {
      ASSERT_LT(c[0], c[2]);
    }
  }
  EXPECT_NEAR(linearToSrgb(0.214041f), 0.5f, 1e-5f);  // sRGB mid-grey
}

TEST(MeshAttributes, NaturalPaletteDarkensWithDurability) {
  const AssetMeshes& base = bandedMeshes(0);
  PaletteParams params = paletteParams(bandedRock(), VertexPaletteParams{});
  const AssetMeshes m = applyPalette(base, params);
  const auto luminance = [](const std::array<float, 3>& c) { return 0.2126f * c[0] + 0.7152f * c[1] + 0.0722f * c[2]; };
  float soft = 0, hard = 0;
  int n_soft = 0, n_hard = 0;
  for (std::size_t i = 0; i < m.rock.positions.size(); ++i) {
    if (m.rock.colluvium[i] > 0.0f) continue;
    if (m.rock.durability[i] <= params.durability_min + 0.01f) soft += luminance(m.rock.colors[i]), ++n_soft;
    if (m.rock.durability[i] >= params.durability_max - 0.01f) hard += luminance(m.rock.colors[i]), ++n_hard;
  }
  ASSERT_GT(n_soft, 0);
  ASSERT_GT(n_hard, 0);
  EXPECT_GT(soft / float(n_soft), 2.0f * hard / float(n_hard)) << "pale soft layers, dark durable ones";
  for (const auto& c : m.rock.colors)
    for (float x : c) ASSERT_TRUE(x >= 0.0f && x <= 1.0f);
}

TEST(MeshAttributes, NaturalPaletteUsesThePresetsLayersAndColluviumColour) {
  const AssetMeshes& base = bandedMeshes(0);
  VertexPaletteParams bake;
  PaletteParams range = paletteParams(bandedRock(), bake);
  // Red for the softest rock, blue for the most durable, green colluvium (all sRGB).
  bake.layers = {{double(range.durability_min), {1.0, 0.0, 0.0}}, {double(range.durability_max), {0.0, 0.0, 1.0}}};
  bake.colluvium_color = SrgbColor{0.0, 1.0, 0.0};
  const PaletteParams params = paletteParams(bandedRock(), bake);
  const AssetMeshes m = applyPalette(base, params);
  int soft = 0, hard = 0;
  for (std::size_t i = 0; i < m.rock.positions.size(); ++i) {
    if (m.rock.colluvium[i] > 0.0f) continue;
    const auto& c = m.rock.colors[i];
    if (m.rock.durability[i] <= params.durability_min + 0.01f) {
      EXPECT_GT(c[0], 0.95f);
      EXPECT_LT(c[2], 0.05f);
      ++soft;
    }
    if (m.rock.durability[i] >= params.durability_max - 0.01f) {
      EXPECT_GT(c[2], 0.95f);
      EXPECT_LT(c[0], 0.05f);
      ++hard;
    }
  }
  EXPECT_GT(soft, 0);
  EXPECT_GT(hard, 0);
  for (const auto& c : m.colluvium.colors) EXPECT_GT(c[1], 0.95f);
}

// ---- exports ----

struct ReadVertex {
  std::array<float, 3> p, n;
  std::array<int, 3> rgb;  // sRGB 8-bit (PLY) or sRGB × 10⁴ (OBJ)
  float durability = 0, colluvium = 0, curvature = 0;
};
struct ReadMesh {
  std::vector<ReadVertex> vertices;
  Faces faces;
};

ReadMesh readPly(const std::filesystem::path& file) {
  const std::string bytes = test::readBytes(file);
  const std::size_t end = bytes.find("end_header\n");
  EXPECT_NE(end, std::string::npos);
  std::istringstream header(bytes.substr(0, end));
  std::string line;
  std::size_t nv = 0, nf = 0;
  std::vector<std::string> props;
  std::string index_type;
  while (std::getline(header, line)) {
    std::istringstream ls(line);
    std::string word, kind, name;
    ls >> word;
    if (word == "format") {
      EXPECT_EQ(line, "format binary_little_endian 1.0");
    }
    if (word == "element") ls >> kind >> (kind == "vertex" ? nv : nf);
    if (word == "property" && props.size() < 12) ls >> kind >> name, props.push_back(name);
    if (word == "property" && line.rfind("property list", 0) == 0) ls >> kind >> kind >> index_type;
  }
  // Indices in 16 bits where every vertex fits them, else 32 (docs/formats.md).
  EXPECT_EQ(index_type, nv <= 65536 ? "ushort" : "uint");
  EXPECT_EQ(props, (std::vector<std::string>{"x", "y", "z", "nx", "ny", "nz", "red", "green", "blue", "durability",
                                             "colluvium", "curvature"}));
  const char* at = bytes.data() + end + 11;
  ReadMesh m;
  m.vertices.resize(nv);
  const auto get = [&](auto& value) {
    std::memcpy(&value, at, sizeof(value));
    at += sizeof(value);
  };
  for (auto& v : m.vertices) {
    for (float& x : v.p) get(x);
    for (float& x : v.n) get(x);
    for (int& c : v.rgb) {
      std::uint8_t b;
      get(b);
      c = b;
    }
    get(v.durability), get(v.colluvium), get(v.curvature);
  }
  for (std::size_t f = 0; f < nf; ++f) {
    std::uint8_t count;
    get(count);
    EXPECT_EQ(count, 3);
    std::array<std::uint32_t, 3> t;
    for (auto& i : t) {
      if (index_type == "ushort") {
        std::uint16_t narrow;
        get(narrow);
        i = narrow;
      } else {
        get(i);
      }
    }
    m.faces.push_back(t);
  }
  EXPECT_EQ(at, bytes.data() + bytes.size());
  return m;
}

// Objects of an OBJ with `v x y z r g b` and `f a//a …` faces, indices made local.
std::map<std::string, ReadMesh> readObj(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::map<std::string, ReadMesh> objects;
  ReadMesh* current = nullptr;
  std::size_t base = 1, seen = 0;
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream ls(line);
    std::string word;
    ls >> word;
    if (word == "o") {
      std::string name;
      ls >> name;
      base = seen + 1;
      current = &objects[name];
    } else if (word == "v") {
      ReadVertex v{};
      float rgb[3];
      ls >> v.p[0] >> v.p[1] >> v.p[2] >> rgb[0] >> rgb[1] >> rgb[2];
      for (int k = 0; k < 3; ++k) v.rgb[k] = int(std::lround(rgb[k] * 1e4f));
      current->vertices.push_back(v);
      ++seen;
    } else if (word == "f") {
      std::array<std::uint32_t, 3> t;
      for (auto& i : t) {
        std::string corner;
        ls >> corner;
        i = std::uint32_t(std::stoul(corner.substr(0, corner.find('/'))) - base);
      }
      current->faces.push_back(t);
    }
  }
  return objects;
}

TEST(MeshExport, PlyRoundTrip) {
  const AssetMeshes& m = bandedMeshes(1);
  test::TempDir dir;
  writePly(m.rock, dir.path() / "rock.ply");
  const ReadMesh r = readPly(dir.path() / "rock.ply");
  ASSERT_EQ(r.vertices.size(), m.rock.positions.size());
  ASSERT_EQ(r.faces, m.rock.triangles);
  for (std::size_t i = 0; i < r.vertices.size(); ++i) {
    const ReadVertex& v = r.vertices[i];
    ASSERT_EQ(v.p, m.rock.positions[i]);
    ASSERT_EQ(v.n, m.rock.normals[i]);
    ASSERT_EQ(v.durability, m.rock.durability[i]);
    ASSERT_EQ(v.colluvium, m.rock.colluvium[i]);
    ASSERT_EQ(v.curvature, m.rock.curvature[i]);
    for (int k = 0; k < 3; ++k)
      ASSERT_NEAR(v.rgb[k] / 255.0f, linearToSrgb(m.rock.colors[i][k]), 0.5f / 255.0f + 1e-6f);
  }
}

TEST(MeshExport, ObjRoundTrip) {
  const AssetMeshes& m = bandedMeshes(1);
  test::TempDir dir;
  writeObj(m, dir.path() / "rock.obj");
  ASSERT_TRUE(std::filesystem::exists(dir.path() / "rock.mtl"));
  EXPECT_NE(test::readBytes(dir.path() / "rock.obj").find("mtllib rock.mtl"), std::string::npos);
  const auto objects = readObj(dir.path() / "rock.obj");
  ASSERT_EQ(objects.size(), 2u);
  for (const SurfaceMesh* s : {&m.rock, &m.colluvium}) {
    const ReadMesh& r = objects.at(s->name);
    ASSERT_EQ(r.vertices.size(), s->positions.size());
    ASSERT_EQ(r.faces, s->triangles);
    for (std::size_t i = 0; i < r.vertices.size(); ++i) {
      // y up (x, z, -y), shortest round-trip formatting
      const auto& q = s->positions[i];
      ASSERT_EQ(r.vertices[i].p, (std::array<float, 3>{q[0], q[2], -q[1]}));
      for (int k = 0; k < 3; ++k) ASSERT_NEAR(r.vertices[i].rgb[k] * 1e-4f, linearToSrgb(s->colors[i][k]), 1e-4f);
    }
  }
}

template <typename T>
std::vector<T> accessorData(const tinygltf::Model& model, int index, int components) {
  const tinygltf::Accessor& a = model.accessors[std::size_t(index)];
  const tinygltf::BufferView& view = model.bufferViews[std::size_t(a.bufferView)];
  const unsigned char* data = model.buffers[std::size_t(view.buffer)].data.data() + view.byteOffset + a.byteOffset;
  std::vector<T> out(a.count * std::size_t(components));
  std::memcpy(out.data(), data, out.size() * sizeof(T));
  return out;
}

TEST(MeshExport, GlbRoundTrip) {
  const AssetMeshes& m = bandedMeshes(1);
  test::TempDir dir;
  writeGlb(m, dir.path() / "rock.glb");
  tinygltf::Model model;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&model, &err, &warn, (dir.path() / "rock.glb").string())) << err;
  EXPECT_TRUE(err.empty()) << err;
  ASSERT_EQ(model.nodes.size(), 2u);
  ASSERT_EQ(model.scenes.size(), 1u);
  EXPECT_EQ(model.scenes[0].nodes.size(), 2u);
  for (const SurfaceMesh* s : {&m.rock, &m.colluvium}) {
    const auto node = std::find_if(model.nodes.begin(), model.nodes.end(),
                                   [&](const tinygltf::Node& n) { return n.name == s->name + "_lod0"; });
    ASSERT_NE(node, model.nodes.end()) << s->name;
    const tinygltf::Primitive& prim = model.meshes[std::size_t(node->mesh)].primitives.at(0);
    EXPECT_EQ(prim.mode, TINYGLTF_MODE_TRIANGLES);
    const auto pos = accessorData<float>(model, prim.attributes.at("POSITION"), 3);
    const auto nrm = accessorData<float>(model, prim.attributes.at("NORMAL"), 3);
    const auto col = accessorData<float>(model, prim.attributes.at("COLOR_0"), 3);
    const auto dur = accessorData<float>(model, prim.attributes.at("_DURABILITY"), 1);
    const auto cov = accessorData<float>(model, prim.attributes.at("_COLLUVIUM"), 1);
    const auto cur = accessorData<float>(model, prim.attributes.at("_CURVATURE"), 1);
    // 16-bit indices where the vertices allow (these meshes have fewer than 65,536).
    EXPECT_EQ(model.accessors[std::size_t(prim.indices)].componentType, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
    const auto idx = accessorData<std::uint16_t>(model, prim.indices, 1);
    ASSERT_EQ(pos.size(), 3 * s->positions.size());
    ASSERT_EQ(idx.size(), 3 * s->triangles.size());
    for (std::size_t i = 0; i < s->positions.size(); ++i) {
      const auto& p = s->positions[i];
      ASSERT_EQ(pos[3 * i + 0], p[0]);  // y-up: (x, z, -y)
      ASSERT_EQ(pos[3 * i + 1], p[2]);
      ASSERT_EQ(pos[3 * i + 2], -p[1]);
      ASSERT_EQ(nrm[3 * i + 1], s->normals[i][2]);
      for (int k = 0; k < 3; ++k) ASSERT_EQ(col[3 * i + k], s->colors[i][k]);
      ASSERT_EQ(dur[i], s->durability[i]);
      ASSERT_EQ(cov[i], s->colluvium[i]);
      ASSERT_EQ(cur[i], s->curvature[i]);
    }
    for (std::size_t t = 0; t < s->triangles.size(); ++t)
      for (int k = 0; k < 3; ++k) ASSERT_EQ(idx[3 * t + k], s->triangles[t][k]);
    const auto& bounds = model.accessors[std::size_t(prim.attributes.at("POSITION"))];
    EXPECT_EQ(bounds.minValues.size(), 3u);
    EXPECT_EQ(bounds.maxValues.size(), 3u);
  }
}

// ---- LODs ----

TEST(MeshLods, TriangleCountsNearTargetsAndClosed) {
  const AssetMeshes& m = bandedMeshes(2);
  const std::vector<double> ratios{0.5, 0.25, 0.1};
  const std::vector<AssetMeshes> lods = simplifyLods(m, {ratios});
  ASSERT_EQ(lods.size(), ratios.size());
  for (std::size_t i = 0; i < lods.size(); ++i)
    for (const auto& [full, lod] : {std::pair{&m.rock, &lods[i].rock}, std::pair{&m.colluvium, &lods[i].colluvium}}) {
      const double target = ratios[i] * double(full->triangles.size());
      EXPECT_NEAR(double(lod->triangles.size()) / target, 1.0, 0.1) << full->name << " ratio " << ratios[i];
      expectClosedManifold(*lod);
      EXPECT_GT(signedVolume(*lod), 0.0);
      ASSERT_EQ(lod->colors.size(), lod->positions.size());
      ASSERT_EQ(lod->durability.size(), lod->positions.size());
    }
}

// ---- the stage in the recipe ----

TEST(MeshStage, WritesTheExportsThePresetAsks) {
  test::TempDir dir;
  Preset p = bandedPreset();
  p.mesh.subdivision = 1;
  p.mesh.lods = {0.5};
  p.exports = {"ply", "glb"};
  const VoxelRock& rock = bandedRock();
  const Stopwatch wall;
  const MeshStageResult r = bakeMeshes(rock, p, /*keep_bake_source=*/true);
  const double export_seconds = exportMeshes(r, nullptr, p, dir.path());
  const double wall_seconds = wall.elapsed();
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "rock.ply"));
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "colluvium.ply"));
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "rock.glb"));
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "rock_lod1.glb"));
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "rock.obj"));
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "rock_lod2.glb"));
  for (const auto& e : std::filesystem::directory_iterator(dir.path()))
    EXPECT_NE(e.path().filename().string()[0], '.') << "temporary left behind: " << e.path();
  // The stage times are parts of the call, not of anything before or after it.
  EXPECT_GT(r.times.seconds("extract").value_or(0.0), 0.0);
  EXPECT_GT(export_seconds, 0.0);
  EXPECT_LE(
      *r.times.seconds("extract") + *r.times.seconds("attributes") + *r.times.seconds("subdivide") + export_seconds,
      wall_seconds);
  // The bake source: the refined surface LOD0 was simplified from, finer than it.
  EXPECT_GT(r.bake_source.rock.triangles.size(), r.meshes.rock.triangles.size());
  EXPECT_EQ(r.bake_source.rock.colors.size(), r.bake_source.rock.positions.size());
}

TEST(MeshStage, BakeAssetWritesMeshesAndTimesTheStages) {
  test::TempDir dir;
  Preset p = bandedPreset();
  p.name = "banded";
  p.mesh.subdivision = 1;
  p.mesh.lods = {0.5, 0.25};
  BakeOptions options;
  options.out_dir = dir.path();
  options.stages.render = false;
  bakeAsset(p, options);
  const auto asset = dir.path() / "banded";
  for (const char* file : {"rock.vdb", "rock.ply", "colluvium.ply", "rock.glb", "rock_lod1.glb", "rock_lod2.glb",
                           "asset.json", "stats.json"})
    EXPECT_TRUE(std::filesystem::exists(asset / file)) << file;
  const auto stats = nlohmann::json::parse(test::readBytes(asset / "stats.json"));
  for (const char* stage : {"mesh_extract", "mesh_subdivide", "mesh_attributes", "export"})
    EXPECT_TRUE(stats["stages"].contains(stage)) << stage;

  test::TempDir bare;
  options.out_dir = bare.path();
  options.stages.mesh = false;
  bakeAsset(p, options);
  EXPECT_TRUE(std::filesystem::exists(bare.path() / "banded" / "rock.vdb"));
  EXPECT_FALSE(std::filesystem::exists(bare.path() / "banded" / "rock.glb"));
}

// The curvature attribute is exposure under the bubble graph in effect when
// the simulation ended: a keyframe that changed the bubbles changes it too.
TEST(MeshStage, CurvatureUsesTheLatestKeyframesBubbles) {
  Preset p = bandedPreset();
  p.name = "keyframed";
  p.exports = {"ply"};
  DurabilityKeyframe k;
  k.at = 0.4;  // half-way through the 8 cycles of h = 0.1
  std::vector<BubbleBand> smaller = p.bubbles;
  for (BubbleBand& band : smaller) band.bubble.extents[0] *= 0.5;
  k.bubbles = smaller;
  p.durability.keyframes = {k};

  test::TempDir dir;
  BakeOptions options;
  options.out_dir = dir.path();
  options.stages.render = false;
  bakeAsset(p, options);
  const ReadMesh baked = readPly(dir.path() / "keyframed" / "rock.ply");

  const VoxelRock rock = weatherRock(buildInitialRock(resolveShape(p), p), p).rock;
  Preset at_end = p;
  at_end.bubbles = smaller;
  const SurfaceMesh expected = buildMeshes(rock, at_end).meshes.rock;
  const SurfaceMesh base = buildMeshes(rock, p).meshes.rock;
  ASSERT_EQ(baked.vertices.size(), expected.positions.size());
  ASSERT_EQ(base.curvature.size(), expected.curvature.size());
  std::size_t differ = 0;
  for (std::size_t i = 0; i < expected.curvature.size(); ++i) {
    ASSERT_EQ(baked.vertices[i].curvature, expected.curvature[i]) << "vertex " << i;
    differ += base.curvature[i] != expected.curvature[i];
  }
  // Not vacuous: the base graph's curvature is another attribute.
  EXPECT_GT(differ, expected.curvature.size() / 10);
}

}  // namespace
}  // namespace rockbake
