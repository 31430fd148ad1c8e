// The mesh stage of the recipe (SPEC §3): final grid ─▶ surfaces ─▶ attributes
// ─▶ subdivision ─▶ palette ─▶ files in the asset folder, as the preset's
// `export:` list asks:
//   ply  rock.ply, colluvium.ply (one surface each; colluvium only if any)
//   obj  rock.obj + rock.mtl (both surfaces, one object each)
//   glb  rock.glb (both surfaces, one node each), and rock_lod1.glb, … per mesh.lods ratio
// (`rock.vdb` is written by the recipe after this stage, with `rock_sdf`.) Every file is atomic.
#pragma once

#include <filesystem>
#include <memory>

#include "core/surface_mesh.h"
#include "core/voxel_rock.h"
#include "preset/preset.h"

namespace rockbake {

struct SmoothedSdf;  // io/openvdb_support.h

struct MeshStageResult {
  AssetMeshes meshes;                           // subdivided, attributed, coloured
  std::shared_ptr<const SmoothedSdf> rock_sdf;  // the field the rock surface was extracted from (for rock.vdb)
  double extract_seconds = 0, attributes_seconds = 0, subdivide_seconds = 0, export_seconds = 0;
};

// Whether the preset's `export:` list names `format` ("ply", "obj", "glb", "vdb").
bool exportsFormat(const Preset& preset, const std::string& format);

// Surfaces, attributes, subdivision and palette, in memory (no files).
MeshStageResult buildMeshes(const VoxelRock& rock, const Preset& preset);

// buildMeshes, then the files the preset's `export:` list asks for.
// Throws std::runtime_error on failure (nothing half-written).
MeshStageResult bakeMeshes(const VoxelRock& rock, const Preset& preset, const std::filesystem::path& asset_dir);

}  // namespace rockbake
