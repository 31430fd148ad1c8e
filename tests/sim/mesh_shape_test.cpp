// Artists' blockouts as the initial shape (docs/model.md §8, shape: {mesh}).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>

#include "core/error.h"
#include "geometry/mesh_checks.h"
#include "inputs/mesh_reader.h"
#include "preset/load_preset.h"
#include "sim/shapes.h"
#include "test_support.h"

namespace rockbake {
namespace {

namespace fs = std::filesystem;

using test::icosphere;

void writeObj(const fs::path& file, const TriangleMesh& m, std::size_t skip_faces = 0) {
  std::ofstream out(file);
  for (const auto& p : m.positions) out << "v " << p[0] << ' ' << p[1] << ' ' << p[2] << '\n';
  for (std::size_t i = skip_faces; i < m.triangles.size(); ++i)
    out << "f " << m.triangles[i][0] + 1 << ' ' << m.triangles[i][1] + 1 << ' ' << m.triangles[i][2] + 1 << '\n';
}

void writeBinaryStl(const fs::path& file, const TriangleMesh& m) {
  std::ofstream out(file, std::ios::binary);
  const std::string header(80, ' ');
  out.write(header.data(), 80);
  const std::uint32_t count = std::uint32_t(m.triangles.size());
  out.write(reinterpret_cast<const char*>(&count), 4);
  for (const auto& t : m.triangles) {
    const float normal[3] = {0, 0, 0};
    out.write(reinterpret_cast<const char*>(normal), 12);
    for (std::uint32_t v : t) {
      const float p[3] = {float(m.positions[v][0]), float(m.positions[v][1]), float(m.positions[v][2])};
      out.write(reinterpret_cast<const char*>(p), 12);
    }
    const std::uint16_t attributes = 0;
    out.write(reinterpret_cast<const char*>(&attributes), 2);
  }
}

void writeAsciiPly(const fs::path& file, const TriangleMesh& m) {
  std::ofstream out(file);
  out << "ply\nformat ascii 1.0\nelement vertex " << m.positions.size()
      << "\nproperty float x\nproperty float y\nproperty float z\nelement face " << m.triangles.size()
      << "\nproperty list uchar int vertex_indices\nend_header\n";
  for (const auto& p : m.positions) out << p[0] << ' ' << p[1] << ' ' << p[2] << '\n';
  for (const auto& t : m.triangles) out << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
}

std::string blockoutPreset(const std::string& mesh_file, double scale) {
  return "rockbake: 1\nname: blockout\ngrid: {size: [3, 3, 3], resolution: 80}\n"
         "shape:\n  mesh: {path: " +
         mesh_file + ", scale: " + std::to_string(scale) +
         "}\n"
         "bubbles: [{up_to: 1, bubble: {sphere: {radius: 0.2}}}]\ncycles: 1\n";
}

TEST(MeshShape, AVoxelizedSphereHasTheAnalyticVolume) {
  test::TempDir dir;
  writeObj(dir.path() / "sphere.obj", icosphere(4));
  test::writeText(dir.path() / "p.yaml", blockoutPreset("sphere.obj", 1.2));
  const Preset p = loadPreset(dir.path() / "p.yaml");
  const VoxelRock rock = buildInitialRock(resolveShape(p), p);
  const double h = rock.layout.h;
  const double volume = double(rock.count(Material::Rock)) * h * h * h;
  const double analytic = 4.0 / 3.0 * std::numbers::pi * std::pow(1.2, 3);
  EXPECT_NEAR(volume / analytic, 1.0, 0.03) << volume << " vs " << analytic;
  // Placed like the primitives: centred in x, y and resting on the ground.
  const Vec3d c = test::rockCentroid(rock);
  EXPECT_NEAR(c[0], 1.5, h);
  EXPECT_NEAR(c[1], 1.5, h);
  EXPECT_NEAR(c[2], 1.2, h);
}

TEST(MeshShape, ObjPlyAndStlGiveTheSameRock) {
  test::TempDir dir;
  const TriangleMesh sphere = icosphere(3);
  writeObj(dir.path() / "s.obj", sphere);
  writeBinaryStl(dir.path() / "s.stl", sphere);
  writeAsciiPly(dir.path() / "s.ply", sphere);
  std::vector<std::size_t> counts;
  for (const char* file : {"s.obj", "s.stl", "s.ply"}) {
    test::writeText(dir.path() / "p.yaml", blockoutPreset(file, 1.0));
    const Preset p = loadPreset(dir.path() / "p.yaml");
    counts.push_back(buildInitialRock(resolveShape(p), p).count(Material::Rock));
  }
  // The same shape; STL stores floats and the text formats 6 digits, so a
  // few voxels whose centres sit on the surface may differ.
  EXPECT_GT(counts[0], 1000u);
  EXPECT_NEAR(double(counts[1]), double(counts[0]), 1e-3 * double(counts[0]));
  EXPECT_NEAR(double(counts[2]), double(counts[0]), 1e-3 * double(counts[0]));
}

// A blockout written y up (as DCCs and rockbake's own OBJ write it) stands up with `up: y`; read with
// the default z up it lies on its side, and the bake says how to stand it up.
TEST(MeshShape, AYUpBlockoutStandsUpWithUpY) {
  test::TempDir dir;
  // A column 0.6 × 0.6 × 2.4 (world z up), written y up: a file's (x, y, z) is the world's (x, −z, y).
  TriangleMesh column = icosphere(3);
  for (auto& p : column.positions) p = {0.3 * p[0], 1.2 * p[2], -0.3 * p[1]};
  writeObj(dir.path() / "column.obj", column);
  std::vector<double> heights;
  for (const char* up : {"", ", up: y"}) {
    std::string text = blockoutPreset("column.obj", 1.0);
    text.replace(text.find(", scale: "), 0, up);
    test::writeText(dir.path() / "p.yaml", text);
    const Preset p = loadPreset(dir.path() / "p.yaml");
    const VoxelRock rock = buildInitialRock(resolveShape(p), p);
    double top = 0;
    for (int z = 0; z < rock.layout.nz; ++z)
      for (int y = 0; y < rock.layout.ny; ++y)
        for (int x = 0; x < rock.layout.nx; ++x)
          if (rock.material[rock.layout.index(x, y, z)] == Material::Rock)
            top = std::max(top, rock.layout.center(x, y, z)[2]);
    heights.push_back(top);
  }
  EXPECT_NEAR(heights[0], 0.6, 0.1) << "read z up, the column lies on its side";
  EXPECT_NEAR(heights[1], 2.4, 0.1) << "read y up, it stands";
  // The bake warns about the first, naming the key to set.
  test::writeText(dir.path() / "p.yaml", blockoutPreset("column.obj", 1.0));
  const auto result = test::runRockbake({"lint", (dir.path() / "p.yaml").string()});
  EXPECT_NE(result.output.find("times wider than tall with z up"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("shape.mesh.up: y"), std::string::npos) << result.output;
}

TEST(MeshShape, AnOpenOrBrokenMeshIsRefusedWithAMessage) {
  test::TempDir dir;
  writeObj(dir.path() / "open.obj", icosphere(2), 3);  // three faces missing
  test::writeText(dir.path() / "p.yaml", blockoutPreset("open.obj", 1.0));
  try {
    resolveShape(loadPreset(dir.path() / "p.yaml"));
    FAIL() << "an open mesh was accepted";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("shape.mesh.path"), std::string::npos) << message;
    EXPECT_NE(message.find("open.obj is not closed"), std::string::npos) << message;
    EXPECT_NE(message.find(":5:"), std::string::npos) << message;  // the line of the path in the preset
  }
  test::writeText(dir.path() / "garbage.obj", "v 0 0 0\nf 1 2 3\n");
  test::writeText(dir.path() / "p.yaml", blockoutPreset("garbage.obj", 1.0));
  try {
    resolveShape(loadPreset(dir.path() / "p.yaml"));
    FAIL() << "a mesh with bad indices was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("past the 1 vertices"), std::string::npos) << e.what();
  }
  // Through the command line: exit 2, nothing written.
  test::writeText(dir.path() / "p.yaml", blockoutPreset("open.obj", 1.0));
  const auto result =
      test::runRockbake({"bake", (dir.path() / "p.yaml").string(), "-o", (dir.path() / "out").string()});
  EXPECT_EQ(result.exit_status, 2) << result.output;
  EXPECT_FALSE(fs::exists(dir.path() / "out"));
}

TEST(MeshShape, TheShippedBlockoutIsClosedAndOutwardFacing) {
  const TriangleMesh boulder = readTriangleMesh(test::sourceDir() / "presets" / "shapes" / "boulder.obj");
  EXPECT_TRUE(findOpenEdges(boulder).empty());
  EXPECT_GT(signedVolume(boulder), 0.0);
}

}  // namespace
}  // namespace rockbake
