#include "pipeline/bake_collision.h"

#include "clasts/place_clasts.h"
#include "collision/collision_hulls.h"
#include "export/collision_glb.h"
#include "preset/schema.h"

namespace rockbake {

AssetCollision bakeCollision(const VoxelRock& rock, const CollisionParams& params, const std::array<double, 3>& pivot,
                             const std::filesystem::path& asset_dir, const GlbConventions& conventions) {
  return writeAssetCollision(buildCollisionHulls(rock, params), params, pivot, asset_dir, nullptr, conventions);
}

AssetCollision writeAssetCollision(CollisionHulls hulls, const CollisionParams& params,
                                   const std::array<double, 3>& pivot, const std::filesystem::path& asset_dir,
                                   const ClastSet* stones, const GlbConventions& conventions) {
  const std::string& prefix = conventions.mesh_prefix;
  if (params.colluvium && stones)
    for (std::size_t k = 0; k < stones->stones.size() && k < std::size_t(params.max_hulls); ++k) {
      const ClastInstance& stone = stones->stones[k];
      std::vector<Vec3d> points;
      for (const auto& v : stones->shapes.at(std::size_t(stone.shape)).positions)
        points.push_back(add(clastVertex(stone, v), pivot));  // the stones lie about the pivot; hulls in the world
      hulls.stones.push_back(stoneHull(points, params.max_vertices));
    }
  writeCollisionGlb(hulls, pivot, params.naming, asset_dir / kCollisionFile, conventions);
  AssetCollision described;
  described.file = kCollisionFile;
  described.naming = schema::nameOf(params.naming);
  // The file's node order (collision_glb.h): the rock's hulls, the colluvium's, the stones'.
  for (const auto& [surface, list] : {std::pair{"rock", &hulls.rock}, std::pair{"colluvium", &hulls.colluvium}})
    for (std::size_t i = 0; i < list->size(); ++i)
      described.hulls.push_back(
          {collisionNodeName(params.naming, surface, i, prefix), (*list)[i].positions.size(), (*list)[i].volume});
  for (std::size_t k = 0; k < hulls.stones.size(); ++k)
    described.hulls.push_back(
        {stoneCollisionNodeName(params.naming, k, prefix), hulls.stones[k].positions.size(), hulls.stones[k].volume});
  return described;
}

}  // namespace rockbake
