// The export phase of the recipe (docs/formats.md): the mesh files the preset's `export:`
// list asks for, from the mesh stage's LODs (pipeline/bake_meshes.h) and, when the bake made
// one, the texture set's (texture/texture_set.h: the same LODs split along UV seams, with uvs,
// tangents and maps in textures/):
//   ply  rock.ply, colluvium.ply: LOD0 as the mesh stage made it, one surface each (welded,
//        no uvs; colluvium only if any)
//   obj  rock.obj + rock.mtl: LOD0, both surfaces, one object each, y up; textured: `vt` per
//        face corner and the maps in the MTL
//   glb  rock.glb (nodes rock_lod0, colluvium_lod0), rock_lod1.glb, … per mesh.lods entry;
//        textured: TEXCOORD_0, TANGENT and each surface's material with the LOD's maps
// The files are written concurrently, each atomically. (`rock.vdb` is the recipe's, with
// `rock_sdf`.) Throws std::runtime_error on failure (nothing half-written).
#pragma once

#include <filesystem>

#include "export/glb_file.h"
#include "pipeline/bake_meshes.h"
#include "preset/preset.h"
#include "texture/texture_set.h"

namespace rockbake {

// The folder of an asset that holds its texture set: OUT/<name>/textures/.
inline constexpr const char* kTextureFolder = "textures";

// `textures`: the texture set baked from `meshes`' LODs (LOD0 first), or null; `clasts`: the
// stones every GLB carries (export/glb_file.h), or null. Returns the seconds it took (wall clock).
double exportMeshes(const MeshStageResult& meshes, const TextureSet* textures, const Preset& preset,
                    const std::filesystem::path& asset_dir, const ClastSet* clasts = nullptr);

// LOD `lod`'s maps in `textures`, as URIs relative to the asset folder.
MaterialMaps lodMaterialMaps(const TextureSet& textures, int lod);

}  // namespace rockbake
