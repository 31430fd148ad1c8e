// Stones on the debris apron as plain data between the clast phase and the export and render
// stages (docs/model.md §13, docs/meshes.md "Clasts"): a few shared stone meshes and the stones
// placed on the apron, each an instance of one of them. Same frame as AssetMeshes: world units,
// z up, about the asset's pivot.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "core/surface_mesh.h"
#include "core/vec3.h"

namespace rockbake {

// One stone: shape `shape` rotated, scaled uniformly and moved.
// A vertex v of the shape lands at translation + scale · R(rotation) v.
struct ClastInstance {
  int shape = 0;
  std::array<double, 3> translation{};         // world units, about the pivot
  std::array<double, 4> rotation{0, 0, 0, 1};  // unit quaternion (x, y, z, w), z-up frame
  double scale = 1.0;                          // world units per shape unit: the stone's longest axis
  double foot_distance = 0.0;                  // horizontal distance from the rock's footprint, world units
};

struct ClastSet {
  // The shared meshes: each closed, its longest axis 1 shape unit, centred on its bounding box,
  // resting on its broadest face (its shortest axis along z). Coloured from the rock layer it fell
  // from; with a texture set, unwrapped with tangents (their maps are `maps`).
  std::vector<SurfaceMesh> shapes;
  // Largest first, so that LOD k keeps a prefix: lod_counts[k] stones (the smallest dropped first).
  std::vector<ClastInstance> stones;
  std::vector<std::size_t> lod_counts;  // per LOD, LOD0 first
  // The stones' shared maps, file names relative to the asset folder's textures/ (empty: none).
  std::string base_color, normal, orm;
  int map_size = 0;
};

// Where vertex `v` of a stone's shape lands, about the pivot (ClastInstance's transform).
inline std::array<double, 3> clastVertex(const ClastInstance& stone, const std::array<float, 3>& v) {
  const auto& q = stone.rotation;
  const Vec3d u{q[0], q[1], q[2]}, p = toVec3d(v);
  // p + 2w (u × p) + 2 u × (u × p): the unit quaternion's rotation.
  const Vec3d t = cross(u, p), tt = cross(u, t);
  std::array<double, 3> out{};
  for (int a = 0; a < 3; ++a) out[a] = stone.translation[a] + stone.scale * (p[a] + 2 * q[3] * t[a] + 2 * tt[a]);
  return out;
}

// The triangles LOD `lod` spends on stones.
inline std::size_t clastTriangles(const ClastSet& set, std::size_t lod) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < set.lod_counts.at(lod); ++i)
    n += set.shapes.at(std::size_t(set.stones[i].shape)).triangles.size();
  return n;
}

}  // namespace rockbake
