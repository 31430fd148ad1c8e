// collision.glb (docs/collision.md): read back with tinygltf, the hulls are
// where the asset's other GLBs put things (about the pivot, y up), named for
// the engine, positions and indices only, each closed, convex and outward.
#include <gtest/gtest.h>

#include "collision/glb_reading.h"
#include "collision/hull_checks.h"
#include "export/collision_glb.h"
#include "export/glb_file.h"
#include "mesh/extract_surfaces.h"

namespace rockbake {
namespace {

using test::accessorValues;
using test::readGlb;

// Built on the surface's mesh in rock.glb, which Unreal pairs them with: the
// name between UCX_ and the last underscore (docs/collision.md).
TEST(CollisionGlb, NodeNamesForEachEngine) {
  EXPECT_EQ(collisionNodeName(HullNaming::Unreal, "rock", 0), "UCX_rock_lod0_00");
  EXPECT_EQ(collisionNodeName(HullNaming::Unreal, "colluvium", 12), "UCX_colluvium_lod0_12");
  EXPECT_EQ(collisionNodeName(HullNaming::Godot, "rock", 3), "rock_lod0_03-convcolonly");
  EXPECT_EQ(collisionNodeName(HullNaming::Godot, "colluvium", 0), "colluvium_lod0_00-convcolonly");
  for (const char* surface : {"rock", "colluvium"}) {
    const std::string name = collisionNodeName(HullNaming::Unreal, surface, 7);
    EXPECT_EQ(name.substr(4, name.rfind('_') - 4), glbMeshName(surface, 0)) << name;
  }
}

TEST(CollisionGlb, HullsInTheAssetFrame) {
  const VoxelRock& rock = test::weatheredGoblin();
  const CollisionHulls hulls = buildCollisionHulls(rock, {.colluvium = true});
  const Vec3d pivot = footprintPivot(rock);
  ASSERT_GT(pivot[0] * pivot[0] + pivot[1] * pivot[1], 0.0);  // so that moving it is seen
  test::TempDir dir;
  for (const HullNaming naming : {HullNaming::Unreal, HullNaming::Godot}) {
    const auto file = dir.path() / "collision.glb";
    writeCollisionGlb(hulls, pivot, naming, file);
    const tinygltf::Model model = readGlb(file);
    ASSERT_EQ(model.scenes.size(), 1u);
    ASSERT_EQ(model.nodes.size(), hulls.rock.size() + hulls.colluvium.size());
    ASSERT_EQ(model.scenes[0].nodes.size(), model.nodes.size());
    std::size_t n = 0;
    for (const auto& [surface, list] : {std::pair{"rock", &hulls.rock}, std::pair{"colluvium", &hulls.colluvium}})
      for (std::size_t i = 0; i < list->size(); ++i, ++n) {
        const ConvexHull& hull = (*list)[i];
        const tinygltf::Node& node = model.nodes[std::size_t(model.scenes[0].nodes[n])];
        EXPECT_EQ(node.name, collisionNodeName(naming, surface, i));
        EXPECT_TRUE(node.translation.empty() && node.rotation.empty() && node.matrix.empty());
        const tinygltf::Mesh& mesh = model.meshes[std::size_t(node.mesh)];
        EXPECT_EQ(mesh.name, node.name);
        ASSERT_EQ(mesh.primitives.size(), 1u);
        const tinygltf::Primitive& p = mesh.primitives[0];
        EXPECT_EQ(p.mode, TINYGLTF_MODE_TRIANGLES);
        ASSERT_EQ(p.attributes.size(), 1u);  // positions only
        const std::vector<float> xyz = accessorValues<float>(model, p.attributes.at("POSITION"), 3);
        const std::vector<std::uint16_t> corners = accessorValues<std::uint16_t>(model, p.indices, 1);
        ASSERT_EQ(xyz.size(), 3 * hull.positions.size());
        ASSERT_EQ(corners.size(), 3 * hull.triangles.size());
        // The file's hull, back in z-up world units about the pivot.
        ConvexHull read;
        read.volume = hull.volume;
        for (std::size_t v = 0; v < hull.positions.size(); ++v) {
          const Vec3d& w = hull.positions[v];
          EXPECT_EQ(xyz[3 * v + 0], float(w[0] - pivot[0]));
          EXPECT_EQ(xyz[3 * v + 1], float(w[2] - pivot[2]));  // y up
          EXPECT_EQ(xyz[3 * v + 2], -float(w[1] - pivot[1]));
          read.positions.push_back({xyz[3 * v], -double(xyz[3 * v + 2]), xyz[3 * v + 1]});
        }
        for (std::size_t t = 0; t < hull.triangles.size(); ++t) {
          for (int c = 0; c < 3; ++c) EXPECT_EQ(corners[3 * t + std::size_t(c)], hull.triangles[t][std::size_t(c)]);
          read.triangles.push_back({corners[3 * t], corners[3 * t + 1], corners[3 * t + 2]});
        }
        // Floats a few units from the origin round by about 1e-7 units: convex
        // within a ten-thousandth of a voxel.
        test::expectClosedConvexOutward(read, 1e-4 * rock.layout.h, node.name, 1e-5);
      }
  }
}

TEST(CollisionGlb, NoHullsIsAnEmptyScene) {
  test::TempDir dir;
  writeCollisionGlb({}, {0, 0, 0}, HullNaming::Unreal, dir.path() / "collision.glb");
  const tinygltf::Model model = readGlb(dir.path() / "collision.glb");
  EXPECT_TRUE(model.nodes.empty());
  EXPECT_TRUE(model.buffers.empty());
}

}  // namespace
}  // namespace rockbake
