// collision.glb (docs/collision.md): binary glTF 2.0 via tinygltf, written
// atomically, one mesh and one node per convex hull (collision/collision_hulls.h):
// POSITION (with its bounds) and triangle indices, nothing else. The asset's
// frame, as in every GLB (glb_file.h): positions about the pivot, y up, the
// point (x, y, z) stored as (x, z, −y), in metres (GlbConventions::meters_per_unit). Each hull stays closed,
// convex and counter-clockwise seen from outside (the change of axes is a rotation).
// Nodes are named for the engine that reads them (collisionNodeName).
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>

#include "collision/collision_hulls.h"
#include "export/glb_file.h"
#include "preset/preset.h"

namespace rockbake {

// The node (and mesh) name of `surface`'s ("rock", "colluvium") hull `index`
// (0..99), built on the name of the surface's mesh in rock.glb (glbMeshName(surface, 0, prefix),
// "rock_lod0"), so that Unreal pairs the hulls with that mesh: Unreal
// "UCX_rock_lod0_00", Godot "rock_lod0_00-convcolonly". `prefix`: GlbConventions::mesh_prefix.
std::string collisionNodeName(HullNaming naming, const std::string& surface, std::size_t index,
                              const std::string& prefix = {});

// The node name of stone k's hull, built on its node in rock.glb (clast_<k>): Unreal
// "UCX_clast_<k>_00", Godot "clast_<k>_00-convcolonly".
std::string stoneCollisionNodeName(HullNaming naming, std::size_t stone, const std::string& prefix = {});

// `pivot`: the world position of the asset's origin (footprintPivot). The rock's
// hulls come first, then the colluvium's, then the stones'. Throws std::runtime_error on failure.
// `conventions`: the mesh prefix and the unit of rock.glb's (images are not used).
void writeCollisionGlb(const CollisionHulls& hulls, const Vec3d& pivot, HullNaming naming,
                       const std::filesystem::path& file, const GlbConventions& conventions = {});

}  // namespace rockbake
