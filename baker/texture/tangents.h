// Tangent frames (docs/textures.md) in the MikkTSpace convention (Mikkelsen, "Simulation of
// Wrinkled Surfaces Revisited", 2008), the one glTF 2.0 names for TANGENT and Blender,
// Unreal, Unity and the bakers compute, written from that description:
//   - each triangle's tangent and bitangent are the directions of increasing s and t over it,
//     from its positions and texture coordinates (s, t) = (u, 1 − v): glTF's v runs down the
//     image, MikkTSpace's t up it, so the bitangent points up the image (+Y, OpenGL);
//   - at each corner both are projected into the plane of the vertex's normal, normalised and
//     weighted by the corner's angle (measured in that plane);
//   - a vertex's tangent is the normalised sum over its triangles (it lies in the normal's
//     plane), and its handedness w = +1 where its triangles keep the (s, t) orientation of
//     the surface, −1 where they mirror it.
// glTF clients rebuild the frame as bitangent = cross(normal, tangent.xyz) · w, and the map
// baker (bake_maps.h) encodes normals in these very frames.
//
// A vertex is taken as the mesh gives it (MikkTSpace also welds vertices equal in position,
// normal and uv; an atlas's vertices never are within a chart). Where a vertex's triangles
// disagree on orientation (not in uvAtlas's output, whose charts never fold), the side with
// the greater angle wins. Triangles without area in space or in uv add nothing; a vertex with
// nothing gets a tangent perpendicular to its normal, w = +1.
#pragma once

#include "core/surface_mesh.h"

namespace rockbake {

// Fills mesh.tangents (one per vertex) from positions, normals, uvs and triangles.
// Throws std::invalid_argument if normals or uvs are missing.
void computeTangents(SurfaceMesh& mesh);

}  // namespace rockbake
