// The mesh stage of the recipe (docs/meshes.md): final grid ─▶ surfaces ─▶ attributes
// ─▶ subdivision ─▶ volume matched to the voxels ─▶ surface detail ─▶ palette
// ─▶ pivot ─▶ LOD0 (simplified to mesh.max_error) ─▶ files in the asset folder,
// as the preset's `export:` list asks, every mesh file holding LOD0:
//   ply  rock.ply, colluvium.ply (one surface each; colluvium only if any)
//   obj  rock.obj + rock.mtl (both surfaces, one object each, y up)
//   glb  rock.glb (both surfaces, one node each: rock_lod0, colluvium_lod0), and
//        rock_lod1.glb, … per mesh.lods entry (nodes rock_lod1, colluvium_lod1, …)
// (`rock.vdb` is written by the recipe after this stage, with `rock_sdf`.) Every file is atomic.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "core/surface_mesh.h"
#include "core/voxel_rock.h"
#include "preset/preset.h"

namespace rockbake {

struct SmoothedSdf;  // core/openvdb_support.h

struct MeshStageResult {
  AssetMeshes meshes;                           // LOD0: attributed, coloured, about the pivot
  std::vector<AssetMeshes> lods;                // LOD1, … (written with glb only)
  std::vector<std::string> lod_files;           // LOD0, LOD1, …: the file holding each (empty: none)
  std::shared_ptr<const SmoothedSdf> rock_sdf;  // the field the rock surface was extracted from (for rock.vdb)
  std::array<double, 3> pivot{};                // footprintPivot: world position of the meshes' origin
  std::size_t refined_triangles = 0;            // both surfaces before simplification
  int subdivision_levels = 0;                   // Catmull-Clark levels spent (mesh/refinement_levels.h)
  // The bake source, kept only when asked for (keep_bake_source): the finest
  // surface, both surfaces as LOD0 was simplified from them (extraction,
  // subdivision where spent, volume, detail, palette, about the pivot), what the
  // texture stage traces to. Empty otherwise: it is the stage's largest mesh
  // (goblin at 384: 1.3 M triangles, about 50 MB), freed once LOD0 is made.
  AssetMeshes bake_source;
  double extract_seconds = 0, attributes_seconds = 0, subdivide_seconds = 0, simplify_seconds = 0, export_seconds = 0;
};

// Whether the preset's `export:` list names `format` ("ply", "obj", "glb", "vdb").
bool exportsFormat(const Preset& preset, const std::string& format);

// Surfaces, attributes, subdivision and palette, in memory (no files). The
// curvature attribute is exposure under `preset.bubbles`: pass the bubble
// graph in effect when the simulation ended (its latest keyframe's).
MeshStageResult buildMeshes(const VoxelRock& rock, const Preset& preset, bool keep_bake_source = false);

// buildMeshes, then the files the preset's `export:` list asks for.
// Throws std::runtime_error on failure (nothing half-written).
MeshStageResult bakeMeshes(const VoxelRock& rock, const Preset& preset, const std::filesystem::path& asset_dir,
                           bool keep_bake_source = false);

}  // namespace rockbake
