// OBJ + MTL export (docs/meshes.md), both written atomically.
//
// One object (`o`) per non-empty surface, each with its own material from the
// .mtl (named after the surface, white diffuse so vertex colours show).
// Vertices as `v x y z r g b` (colours: the linear colours encoded to sRGB,
// as OBJ viewers display them), normals as `vn`, faces `f a//a b//b c//c`.
// World units, y up as DCCs read OBJ: world (x, y, z) is written (x, z, -y).
#pragma once

#include <filesystem>

#include "core/surface_mesh.h"

namespace rockbake {

// `obj` names the .obj; the .mtl goes beside it with the same stem.
// Throws std::runtime_error on failure.
void writeObj(const AssetMeshes& meshes, const std::filesystem::path& obj);

}  // namespace rockbake
