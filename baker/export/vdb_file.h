// The rock as an OpenVDB file (docs/formats.md, rock.vdb).
// OpenVDB headers stay in the .cpp: they are heavy to compile.
#pragma once

#include <filesystem>
#include <iosfwd>

#include "core/voxel_rock.h"

namespace rockbake {

struct SmoothedSdf;  // platform/openvdb_support.h

// Writes, atomically, one .vdb holding
//   BoolGrid  "rock"        active, true on Material::Rock voxels
//   BoolGrid  "colluvium"   active, true on Material::Colluvium voxels
//   FloatGrid "durability"  rock voxels' durability, background 0
//   FloatGrid "rock_sdf"    GRID_LEVEL_SET, negative inside, world units: the
//                           mesh stage's smoothed field when `rock_sdf` is given
//                           (the surface the meshes were made from), else a narrow
//                           band (3 voxels each side) of the rock occupancy
// and, when the rock has a history (core/voxel_rock.h; docs/model.md §14), on rock voxels:
//   FloatGrid "exposed_at"      the cycle a face first opened to air (0: the blockout), background −1
//   FloatGrid "covered_until"   the last cycle it had a face on colluvium, background −1
//   FloatGrid "covered_cycles"  how many cycles it had a face on colluvium, background 0
//   FloatGrid "scarred_at"      the last cycle rockfall opened its surface, background −1
// Index space is the voxel (x, y, z) of the VoxelRock; every grid shares one
// transform, mapping index (i, j, k) to layout.center(i, j, k) - pivot, where
// pivot = footprintPivot(rock) (the meshes' origin, the footprint's centre on
// the ground). File metadata: creator "rockbake", voxel_size h, pivot. The bytes are a pure function of the rock: the
// archive's random UUID is replaced by one hashed from the rest of the file,
// so the same rock gives the same file at any thread count.
// Throws std::runtime_error on failure.
// `sink`: how deep the asset is sunk (footprintPivot's, mesh.sink resolved).
void writeRockVdb(const VoxelRock& rock, const std::filesystem::path& file, const SmoothedSdf* rock_sdf = nullptr,
                  double sink = 0.0);

// The same bytes to a stream that can seek back (a std::ostringstream, a file):
// the archive's UUID is patched in after the grids are written. The studio
// serves rock.vdb this way, without a file (docs/studio.md). Throws
// std::runtime_error naming the stream as "rock.vdb".
void writeRockVdb(const VoxelRock& rock, std::ostream& out, const SmoothedSdf* rock_sdf = nullptr);

// Reads a file written by writeRockVdb back into `layout`: material from the
// "rock" and "colluvium" grids (Air elsewhere), durability from "durability",
// integrity 1. Throws std::runtime_error if the file is unreadable, a grid is
// missing, or the file's transform or voxels do not fit the layout.
VoxelRock readRockVdb(const std::filesystem::path& file, const GridLayout& layout);

}  // namespace rockbake
