// OBJ + MTL export (docs/meshes.md), both written atomically.
//
// One object (`o`) per non-empty surface, each with its own material from the
// .mtl (named after the surface, white diffuse so vertex colours show).
// Vertices as `v x y z r g b` (colours: the linear colours encoded to sRGB,
// as OBJ viewers display them), normals as `vn`, faces `f a//a b//b c//c`.
// World units, y up as DCCs read OBJ: world (x, y, z) is written (x, z, -y).
//
// Textured (docs/textures.md): the faces also carry texture coordinates,
// `vt u v` (v up, as OBJ has it: 1 − glTF's v) and `f a/ta/a …`, while `v` and
// `vn` stay one per vertex of the welded surface (a UV seam is a seam in `vt`
// only, so the surface stays closed), and each material names the maps:
// `map_Kd` (base colour), `norm` and `map_Bump -bm 1` (the tangent-space
// normal map: the PBR extension's keyword, and the one Blender's importer
// wires to a normal-map node), `disp` (the height, LOD0's displacement) and
// `Pm 0` (not metal). The ORM map is not named: MTL has no packed map, and a
// reader would take its luminance for roughness.
#pragma once

#include <filesystem>

#include "core/surface_mesh.h"
#include "export/glb_file.h"

namespace rockbake {

// `obj` names the .obj; the .mtl goes beside it with the same stem. `uvs`: the same
// triangles in the same order, split along UV seams with uvs (the texture set's LOD0), whose
// corners give the faces their `vt`; `maps`: their URIs relative to the .obj. Throws
// std::runtime_error on failure, or when `uvs` does not match `meshes` triangle for triangle.
void writeObj(const AssetMeshes& meshes, const std::filesystem::path& obj, const AssetMeshes* uvs = nullptr,
              const MaterialMaps& maps = {});

}  // namespace rockbake
