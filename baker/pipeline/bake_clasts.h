// The clast phase of the recipe (docs/model.md §13): stones on the debris apron.
//
// Each of the preset's `clasts.shapes` stone meshes is a small weathered rock made by the same
// simulation at small scale: a jointed block (clasts/clast_blocks.h) of the rock's durability at
// a seeded rock voxel, rounded by spheroidal weathering for two to five cycles on a 24-voxel grid,
// meshed by the mesh stage and simplified to about kClastShapeTriangles triangles, coloured by the
// preset's palette. The stones are then laid on LOD0's apron (clasts/place_clasts.h), and each
// LOD keeps its largest stones within a share of its triangle budget (clastLodCounts).
#pragma once

#include <filesystem>
#include <vector>

#include "core/clast_set.h"
#include "core/voxel_rock.h"
#include "pipeline/bake_meshes.h"
#include "preset/preset.h"

namespace rockbake {

inline constexpr int kClastShapeTriangles = 160;
// At LOD k >= 1 the stones take at most this share of the LOD's triangle budget; the last LOD has none.
inline constexpr double kClastLodShare = 0.15;

struct ClastStage {
  ClastSet set;
  std::vector<SurfaceMesh> sources;  // each shape's finest surface, in its frame (for its maps)
};

// The stone meshes and the stones on LOD0's apron (no maps, no LOD counts). Empty without
// `preset.clasts`, without ground or without colluvium.
ClastStage bakeClasts(const VoxelRock& rock, const MeshStageResult& meshes, const Preset& preset);

// How many stones each LOD keeps (largest first), given LOD k >= 1's triangle budget for the rock
// and colluvium (`budgets`, mesh.lods as counts): all at LOD0; at LOD k those whose meshes fit in
// kClastLodShare of its budget; none at the last LOD (when there is more than LOD0).
std::vector<std::size_t> clastLodCounts(const ClastSet& set, const std::vector<std::size_t>& budgets);

// Unwraps the stone meshes into one shared atlas and bakes their base colour, normal and ORM maps
// from their finest surfaces into `folder` as <name>_Clasts_*.png (texture/texture_set.h), at a
// quarter of texture.size (256 … 1024). Replaces set.shapes by the unwrapped meshes.
// `name`: the texture set's (pipeline/delivery_profile.h); the files are <name>_Clasts_BaseColor.png, ….
// `directx_normals`: the normal map in DirectX's convention (texture_set.h).
void textureClasts(ClastStage& stage, const Preset& preset, const std::filesystem::path& folder,
                   const std::string& name, bool directx_normals = false);

}  // namespace rockbake
