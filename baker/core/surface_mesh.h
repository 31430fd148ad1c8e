// Meshes as plain data between the inputs, mesh, export and render stages (docs/meshes.md).
// World units, z up (the simulation's frame). Colours are linear RGB in [0, 1].
//
// Per-vertex arrays are listed once, in kVertexArrays below: every operation
// that adds, drops, reorders or copies vertices (geometry/vertex_remap.h: remap,
// compaction, welding, splitting) carries each array listed there, and each
// must be empty or hold one value per position. Adding a per-vertex array to
// SurfaceMesh means adding it to kVertexArrays too; the static_assert below
// the list fails until it is listed there (or, for anything not per vertex,
// in the assertion itself).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <tuple>
#include <vector>

namespace rockbake {

struct SurfaceMesh {
  std::string name;                                     // "rock" or "colluvium"
  std::vector<std::array<float, 3>> positions;          // world units
  std::vector<std::array<float, 3>> normals;            // unit length, outward
  std::vector<std::array<std::uint32_t, 3>> triangles;  // counter-clockwise seen from outside
  // Quad faces, counter-clockwise seen from outside. Only the extraction stage's
  // quad-dominant output has them (faces = triangles ∪ quads); subdivideSurface
  // returns triangles only, and the exporters and the renderer read triangles only.
  std::vector<std::array<std::uint32_t, 4>> quads;
  // Per-vertex baked attributes.
  std::vector<float> durability;             // D at the surface (0 on colluvium)
  std::vector<float> colluvium;              // 0..1 coverage
  std::vector<float> curvature;              // calibrated exposure s, 0..1 (½ flat)
  std::vector<float> altitude;               // normalised altitude, 0 at the ground, 1 at the top of grid.size
  std::vector<std::array<float, 3>> colors;  // linear RGB from the preset's palette
  // The weathering history at the surface (mesh/bake_attributes.h), empty without a look, each 0..1:
  // exposure age (0 exposed at the last cycle … 0.98 the initial surface, saturating over a quarter of the run),
  // rockfall-scar freshness (0 never … 1 opened at the last cycle), burial (the share of the run spent under
  // colluvium).
  std::vector<std::array<float, 3>> history;
  // The look made from it (mesh/surface_look.h), the History map's RGBA, each 0..1: exposure age
  // (scars are young), stain and varnish, moisture, dust. Empty without a look.
  std::vector<std::array<float, 4>> look;
  // Texture coordinates, empty until the texture stage unwraps the mesh (texture/uv_atlas.h):
  // [0, 1], glTF's convention (u right, v down, (0, 0) the image's top-left texel corner).
  std::vector<std::array<float, 2>> uvs;
  // Tangent frames, with uvs (texture/tangents.h): unit xyz perpendicular to the normal, w = ±1;
  // the bitangent is cross(normal, xyz) · w, as glTF's TANGENT.
  std::vector<std::array<float, 4>> tangents;
};

// One per-vertex array of SurfaceMesh: its name (for messages) and its member.
template <class T>
struct VertexArray {
  const char* name;
  std::vector<T> SurfaceMesh::*member;
};

// Every per-vertex array of SurfaceMesh, positions first.
inline constexpr std::tuple kVertexArrays{
    VertexArray<std::array<float, 3>>{"positions", &SurfaceMesh::positions},
    VertexArray<std::array<float, 3>>{"normals", &SurfaceMesh::normals},
    VertexArray<float>{"durability", &SurfaceMesh::durability},
    VertexArray<float>{"colluvium", &SurfaceMesh::colluvium},
    VertexArray<float>{"curvature", &SurfaceMesh::curvature},
    VertexArray<float>{"altitude", &SurfaceMesh::altitude},
    VertexArray<std::array<float, 3>>{"colors", &SurfaceMesh::colors},
    VertexArray<std::array<float, 3>>{"history", &SurfaceMesh::history},
    VertexArray<std::array<float, 4>>{"look", &SurfaceMesh::look},
    VertexArray<std::array<float, 2>>{"uvs", &SurfaceMesh::uvs},
    VertexArray<std::array<float, 4>>{"tangents", &SurfaceMesh::tangents},
};

// Calls visit(name, array) for each array in kVertexArrays, in order; `Mesh`
// is SurfaceMesh or const SurfaceMesh.
template <class Mesh, class Visit>
void forEachVertexArray(Mesh& mesh, Visit&& visit) {
  std::apply([&](const auto&... array) { (visit(array.name, mesh.*(array.member)), ...); }, kVertexArrays);
}

// SurfaceMesh is its name, its faces and the arrays kVertexArrays lists, and nothing else.
static_assert(sizeof(SurfaceMesh) ==
                  sizeof(std::string) + sizeof(SurfaceMesh::triangles) + sizeof(SurfaceMesh::quads) +
                      std::apply([](const auto&... array) { return (sizeof(SurfaceMesh{}.*(array.member)) + ...); },
                                 kVertexArrays),
              "a SurfaceMesh member is missing from kVertexArrays (per-vertex) or from this assertion");

// A triangle soup with shared vertices, double precision: an artist's blockout
// as read (file units), before it is voxelized.
struct TriangleMesh {
  std::vector<std::array<double, 3>> positions;
  std::vector<std::array<std::uint32_t, 3>> triangles;
};

struct AssetMeshes {
  SurfaceMesh rock;
  SurfaceMesh colluvium;                            // empty when there is none
  std::array<float, 3> bounds_min{}, bounds_max{};  // over both meshes, world units
  // The preset's durability range over the rock voxels (what COLOR_1 normalises by).
  std::array<float, 2> durability_range{0.0f, 1.0f};
};

}  // namespace rockbake
