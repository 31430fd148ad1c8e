#include "pipeline/bake_collision.h"

#include "collision/collision_hulls.h"
#include "export/collision_glb.h"
#include "preset/schema.h"

namespace rockbake {

AssetCollision bakeCollision(const VoxelRock& rock, const CollisionParams& params, const std::array<double, 3>& pivot,
                             const std::filesystem::path& asset_dir) {
  const CollisionHulls hulls = buildCollisionHulls(rock, params);
  writeCollisionGlb(hulls, pivot, params.naming, asset_dir / kCollisionFile);
  AssetCollision described;
  described.file = kCollisionFile;
  described.naming = schema::nameOf(params.naming);
  // The file's node order (collision_glb.h): the rock's hulls, then the colluvium's.
  for (const auto& [surface, list] : {std::pair{"rock", &hulls.rock}, std::pair{"colluvium", &hulls.colluvium}})
    for (std::size_t i = 0; i < list->size(); ++i)
      described.hulls.push_back(
          {collisionNodeName(params.naming, surface, i), (*list)[i].positions.size(), (*list)[i].volume});
  return described;
}

}  // namespace rockbake
