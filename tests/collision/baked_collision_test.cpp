// collision.glb as a bake writes it (docs/collision.md, "In a bake"), through
// the real rockbake: beside the meshes, hulls named after rock.glb's meshes for
// the engine collision.naming names, in rock.glb's frame, each closed, convex
// and under the caps; asset.json's "collision" entry agrees with the file, and
// the manifest lists it. No collision.glb without meshes or without
// `collision` in export:.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <regex>
#include <set>

#include <nlohmann/json.hpp>

#include "collision/glb_reading.h"
#include "collision/hull_checks.h"
#include "test_support.h"

namespace rockbake {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
using test::readBytes;
using test::runRockbake;

// goblin (rock, joints, colluvium) at a test resolution, without the render.
fs::path bakeGoblin(const fs::path& out, const std::vector<std::string>& sets) {
  std::vector<std::string> args = {
      "bake",      (test::sourceDir() / "presets" / "goblin.yaml").string(), "--resolution", "32", "--no-render", "-o",
      out.string()};
  for (const std::string& s : sets) args.insert(args.end(), {"--set", s});
  const auto result = runRockbake(args);
  EXPECT_EQ(result.exit_status, 0) << result.output;
  return out / "goblin";
}

struct Box {
  Vec3d lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  void add(const Vec3d& p) {
    for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], p[a]), hi[a] = std::max(hi[a], p[a]);
  }
};

// The bounds of rock.glb's node `name`, in the asset's z-up frame.
Box meshBounds(const tinygltf::Model& model, const std::string& name) {
  Box box;
  for (const tinygltf::Node& node : model.nodes) {
    if (node.name != name) continue;
    const tinygltf::Primitive& p = model.meshes.at(std::size_t(node.mesh)).primitives.at(0);
    const std::vector<float> xyz = test::accessorValues<float>(model, p.attributes.at("POSITION"), 3);
    for (std::size_t v = 0; v + 2 < xyz.size(); v += 3) box.add({xyz[v], -double(xyz[v + 2]), xyz[v + 1]});
  }
  return box;
}

// What a bake's collision.glb must be, and asset.json's and the manifest's account of it.
void expectCollisionAsset(const fs::path& asset, const std::string& naming, bool colluvium, double units_per_meter) {
  ASSERT_TRUE(fs::is_regular_file(asset / "collision.glb"));
  const std::vector<test::NamedHull> hulls = test::readHulls(test::readGlb(asset / "collision.glb"));
  const tinygltf::Model render_meshes = test::readGlb(asset / "rock.glb");
  std::set<std::string> render_names;
  for (const tinygltf::Node& node : render_meshes.nodes) render_names.insert(node.name);

  // Names: the engine's pattern around the name of a mesh (or, for a stone, the node) rock.glb holds.
  const std::regex pattern(naming == "unreal" ? "UCX_(rock_lod0|colluvium_lod0|clast_[0-9]+)_([0-9]{2})"
                                              : "(rock_lod0|colluvium_lod0|clast_[0-9]+)_([0-9]{2})-convcolonly");
  std::map<std::string, int> per_surface;
  Box rock_hulls;
  for (const test::NamedHull& h : hulls) {
    std::smatch m;
    ASSERT_TRUE(std::regex_match(h.name, m, pattern)) << h.name;
    EXPECT_TRUE(render_names.count(m[1].str())) << h.name << " pairs with no mesh of rock.glb";
    EXPECT_EQ(std::stoi(m[2].str()), per_surface[m[1].str()]++) << h.name << ": hulls numbered from 00 in order";
    EXPECT_LE(h.hull.positions.size(), 64u) << h.name;
    test::expectClosedConvexOutward(h.hull, 1e-4, h.name, 1e-12);
    if (m[1].str() == "rock_lod0")
      for (const Vec3d& p : h.hull.positions) rock_hulls.add(p);
  }
  EXPECT_GE(per_surface["rock_lod0"], 2);
  EXPECT_LE(per_surface["rock_lod0"], 16);
  EXPECT_EQ(per_surface.count("colluvium_lod0") > 0, colluvium);

  // The same frame as rock.glb: the hulls hold the voxels the surface was smoothed from, so their bounds and the
  // surface's agree to within a voxel or two (goblin at 32: 0.1 units, 0.1 / units_per_meter metres).
  const Box surface = meshBounds(render_meshes, "rock_lod0");
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(rock_hulls.lo[a], surface.lo[a], 0.25 / units_per_meter) << "axis " << a;
    EXPECT_NEAR(rock_hulls.hi[a], surface.hi[a], 0.25 / units_per_meter) << "axis " << a;
  }
  EXPECT_NEAR(rock_hulls.lo[2], 0.0, 1e-6) << "the hulls stand on the ground, at the pivot's height";

  // asset.json lists the file's hulls, in its order, volumes in cubic metres.
  const json asset_json = json::parse(readBytes(asset / "asset.json"));
  ASSERT_TRUE(asset_json.contains("collision")) << asset_json.dump(2);
  const json& c = asset_json["collision"];
  EXPECT_EQ(c["file"], "collision.glb");
  EXPECT_EQ(c["naming"], naming);
  ASSERT_EQ(c["hull_count"].get<std::size_t>(), hulls.size());
  ASSERT_EQ(c["hulls"].size(), hulls.size());
  std::size_t vertices = 0;
  for (std::size_t i = 0; i < hulls.size(); ++i) {
    const json& entry = c["hulls"][i];
    EXPECT_EQ(entry["node"], hulls[i].name);
    EXPECT_EQ(entry["vertices"].get<std::size_t>(), hulls[i].hull.positions.size());
    // collision.glb is in metres whatever units_per_meter (docs/delivery.md, "Units").
    const double m3 = hulls[i].hull.volume;
    EXPECT_NEAR(entry["volume_m3"].get<double>(), m3, 1e-5 * m3 + 1e-9) << hulls[i].name;
    vertices += hulls[i].hull.positions.size();
  }
  EXPECT_EQ(c["vertex_count"].get<std::size_t>(), vertices);

  // Listed like every output, and timed.
  const json manifest = json::parse(readBytes(asset / "manifest.json"));
  const auto listed = std::find_if(manifest["outputs"].begin(), manifest["outputs"].end(),
                                   [](const json& o) { return o["path"] == "collision.glb"; });
  ASSERT_NE(listed, manifest["outputs"].end());
  EXPECT_EQ((*listed)["size"].get<std::uintmax_t>(), fs::file_size(asset / "collision.glb"));
  const json stats = json::parse(readBytes(asset / "stats.json"));
  EXPECT_GE(stats["stages"]["collision"].get<double>(), 0.0);
}

TEST(BakedCollision, UnrealNamesByDefault) {
  test::TempDir dir;
  const fs::path asset = bakeGoblin(dir.path(), {"export=[glb, collision]"});
  expectCollisionAsset(asset, "unreal", false, 1.0);
}

// Godot's names, the colluvium's own hulls, and volumes in cubic metres of centimetre units.
TEST(BakedCollision, GodotNamesColluviumAndUnits) {
  test::TempDir dir;
  const fs::path asset = bakeGoblin(dir.path(), {"export=[glb, collision]", "collision.naming=godot",
                                                 "collision.colluvium=true", "units_per_meter=100"});
  expectCollisionAsset(asset, "godot", true, 100.0);
}

// Without `collision` in export:, or without meshes (--no-mesh: no rock.glb to pair with, no asset.json to list
// them), no collision.glb and no entry.
TEST(BakedCollision, OnlyWhenExportListsItAndWithMeshes) {
  test::TempDir dir;
  const fs::path asset = bakeGoblin(dir.path() / "glb", {"export=[glb]"});
  EXPECT_FALSE(fs::exists(asset / "collision.glb"));
  EXPECT_FALSE(json::parse(readBytes(asset / "asset.json")).contains("collision"));
  EXPECT_FALSE(json::parse(readBytes(asset / "stats.json"))["stages"].contains("collision"));

  const auto result = runRockbake({"bake", (test::sourceDir() / "presets" / "goblin.yaml").string(), "--resolution",
                                   "32", "--no-mesh", "-o", (dir.path() / "no-mesh").string()});
  ASSERT_EQ(result.exit_status, 0) << result.output;
  EXPECT_FALSE(fs::exists(dir.path() / "no-mesh" / "goblin" / "collision.glb"));
  EXPECT_TRUE(fs::exists(dir.path() / "no-mesh" / "goblin" / "rock.vdb"));
}

}  // namespace
}  // namespace rockbake
