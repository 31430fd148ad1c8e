// The mesh stage of the recipe (docs/meshes.md): final grid ─▶ surfaces ─▶ attributes
// ─▶ subdivision ─▶ volume matched to the voxels ─▶ surface detail ─▶ palette
// ─▶ pivot ─▶ the bake source ─▶ LOD0 (simplified to mesh.max_error) ─▶ the LOD chain, in
// memory. The files come later (pipeline/export_meshes.h), once the texture stage has given
// the LODs their uvs and tangents.
//
// The bake source is the finest surface the bake made — extraction, subdivision, volume
// match and detail, coloured and about the pivot, before any simplification — that LOD0 and
// the chain were simplified from: what the texture stage bakes its maps from
// (docs/textures.md). It is the largest thing the stage makes; a caller asks for it only when
// it makes textures, and drops it once done.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/surface_mesh.h"
#include "core/voxel_rock.h"
#include "platform/phase_times.h"
#include "preset/preset.h"

namespace rockbake {

struct SmoothedSdf;  // platform/openvdb_support.h

struct MeshStageResult {
  AssetMeshes meshes;             // LOD0: attributed, coloured, about the pivot
  std::vector<AssetMeshes> lods;  // LOD1, … (made with glb only)
  // The bake source (above), in LOD0's frame, kept only when asked for (keep_bake_source): empty
  // otherwise, freed once LOD0 is made (goblin at 384: 1.3 M triangles, about 50 MB).
  AssetMeshes bake_source;
  std::vector<std::string> lod_files;           // LOD0, LOD1, …: the file holding each (empty: none)
  std::shared_ptr<const SmoothedSdf> rock_sdf;  // the field the rock surface was extracted from (for rock.vdb)
  std::array<double, 3> pivot{};                // footprintPivot: world position of the meshes' origin
  std::size_t refined_triangles = 0;            // both surfaces before simplification
  int subdivision_levels = 0;                   // Catmull-Clark levels spent (mesh/refinement_levels.h)
  PhaseTimes times;                             // "extract", "attributes", "subdivide", "simplify" (LOD0 and the LODs)
};

// Whether the preset's `export:` list names `format` ("ply", "obj", "glb", "vdb").
bool exportsFormat(const Preset& preset, const std::string& format);

// Surfaces, attributes, subdivision and palette, LOD0 and (with keep_bake_source) the bake source, in
// memory (no files; no LOD chain). The curvature attribute is exposure under `bubbles`: the bubble
// graph in effect when the simulation ended (its latest keyframe's); null: `preset.bubbles`.
MeshStageResult buildMeshes(const VoxelRock& rock, const Preset& preset, bool keep_bake_source = false,
                            const std::vector<BubbleBand>* bubbles = nullptr);

// The LOD chain of `r.meshes` to `targets` (mesh.lods' form) when the preset exports glb, and
// the name of the file that will hold each LOD (`lod_files`). No files.
void addLods(MeshStageResult& r, const Preset& preset, const std::vector<double>& targets);

// LOD k >= 1's triangle budget for `lod0_triangles` triangles in LOD0: mesh.lods' entry as a count.
std::vector<std::size_t> lodBudgets(const Preset& preset, std::size_t lod0_triangles);

// buildMeshes, then the LOD chain (`mesh.lods`) when the preset exports glb, and the name of
// the file that will hold each LOD (`lod_files`). No files.
MeshStageResult bakeMeshes(const VoxelRock& rock, const Preset& preset, bool keep_bake_source = false);

}  // namespace rockbake
