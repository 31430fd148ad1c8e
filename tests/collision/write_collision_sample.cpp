// Writes a collision.glb for the tests that read it with other tools (the glTF
// validator, Blender): the default preset at resolution 40, its rock and its
// colluvium hulled, once named for Unreal (collision.glb) and once for Godot
// (collision_godot.glb), and expected.json, what each file holds: per node its
// name, vertices, triangles and bounds in the asset's frame, z up.
//   rockbake_collision_sample OUT_DIR
#include <cstdio>
#include <fstream>

#include <nlohmann/json.hpp>

#include "collision/collision_hulls.h"
#include "export/collision_glb.h"
#include "inputs/resolve_shape.h"
#include "mesh/extract_surfaces.h"
#include "preset/load_preset.h"
#include "sim/shapes.h"
#include "sim/weathering.h"

using namespace rockbake;

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: rockbake_collision_sample OUT_DIR\n");
    return 2;
  }
  const std::filesystem::path out = argv[1];
  const Preset p =
      loadPreset(std::filesystem::path(ROCKBAKE_SOURCE_DIR) / "presets" / "goblin.yaml", {{}, std::nullopt, 40});
  const VoxelRock rock = weatherRock(buildInitialRock(resolveShape(p), p), p).rock;
  const CollisionParams params{.colluvium = true};
  const CollisionHulls hulls = buildCollisionHulls(rock, params);
  const Vec3d pivot = footprintPivot(rock);
  nlohmann::json expected;
  expected["max_vertices"] = params.max_vertices;
  for (const auto& [file, naming] :
       {std::pair{"collision.glb", HullNaming::Unreal}, std::pair{"collision_godot.glb", HullNaming::Godot}}) {
    writeCollisionGlb(hulls, pivot, naming, out / file);
    nlohmann::json nodes = nlohmann::json::array();
    for (const auto& [surface, list] : {std::pair{"rock", &hulls.rock}, std::pair{"colluvium", &hulls.colluvium}})
      for (std::size_t i = 0; i < list->size(); ++i) {
        const ConvexHull& h = (*list)[i];
        Vec3d lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
        for (const Vec3d& v : h.positions)
          for (int a = 0; a < 3; ++a)
            lo[a] = std::min(lo[a], v[a] - pivot[a]), hi[a] = std::max(hi[a], v[a] - pivot[a]);
        nodes.push_back({{"name", collisionNodeName(naming, surface, i)},
                         {"vertices", h.positions.size()},
                         {"triangles", h.triangles.size()},
                         {"min", lo},
                         {"max", hi}});
      }
    expected["files"].push_back({{"file", file}, {"nodes", nodes}});
  }
  std::ofstream(out / "expected.json") << expected.dump(2) << "\n";
  std::printf("%zu rock and %zu colluvium hulls in %s\n", hulls.rock.size(), hulls.colluvium.size(), out.c_str());
}
