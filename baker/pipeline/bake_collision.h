// The collision phase of the recipe (docs/collision.md): the final rock's convex
// hulls (collision/collision_hulls.h, with the preset's `collision:` block), written
// to <asset_dir>/collision.glb (export/collision_glb.h) in the asset's frame: about
// `pivot` (the meshes' footprintPivot), y up, in metres, like rock.glb, and named
// after rock.glb's meshes (rock_lod0, colluvium_lod0; `conventions` gives their prefix and the
// unit) so that an engine pairs them. `params.naming` is the hull naming in force (the delivery
// profile's, pipeline/delivery_profile.h).
// Gives what asset.json says of the file. The file is written atomically; throws
// std::runtime_error on failure (Qhull, the write) and std::invalid_argument for
// parameters outside CollisionParams' ranges (a loaded preset has none).
#pragma once

#include <array>
#include <filesystem>

#include "collision/collision_hulls.h"
#include "core/clast_set.h"
#include "core/voxel_rock.h"
#include "export/glb_file.h"
#include "pipeline/asset_json.h"
#include "preset/preset.h"

namespace rockbake {

inline constexpr const char* kCollisionFile = "collision.glb";

AssetCollision bakeCollision(const VoxelRock& rock, const CollisionParams& params, const std::array<double, 3>& pivot,
                             const std::filesystem::path& asset_dir, const GlbConventions& conventions = {});

// The same in two steps, so that the voxels' hulls (the slow part) can be made beside the meshes
// and the stones' added once they lie on the apron: `hulls` from buildCollisionHulls; with
// params.colluvium and `stones`, the hulls of the largest max_hulls stones are added (stoneHull,
// nodes named after the stones' own, stoneCollisionNodeName) before the file is written.
AssetCollision writeAssetCollision(CollisionHulls hulls, const CollisionParams& params,
                                   const std::array<double, 3>& pivot, const std::filesystem::path& asset_dir,
                                   const ClastSet* stones = nullptr, const GlbConventions& conventions = {});

}  // namespace rockbake
