// The bake source as a ray-cast scene (docs/textures.md): both surfaces of the finest mesh
// the bake made, in one Embree 3 scene (robust, watertight triangle tests; the BVH is built
// in parallel and is the same at any thread count). Embree's headers stay in ray_source.cpp.
//
// Ties: where a ray meets two triangles at exactly the same distance (an edge or a vertex),
// the lower triangle index wins, so a hit never depends on the BVH's traversal order.
// Queries are thread-safe.
#pragma once

#include <array>
#include <cstdint>
#include <memory>

#include "core/surface_mesh.h"

namespace rockbake {

struct SourceHit {
  bool hit = false;
  std::uint32_t triangle = 0;  // in the surface that was asked for
  float u = 0, v = 0;          // the point is (1 − u − v) · p0 + u · p1 + v · p2
  float distance = 0;          // signed, along the direction (negative: behind the origin)
};

class RaySource {
 public:
  // Triangles of source.rock (surface 0) and source.colluvium (surface 1). Positions are
  // copied; the triangle lists and the normals (the facing rule's) are read in place, so
  // `source` must outlive the RaySource.
  // Throws std::runtime_error if Embree fails.
  explicit RaySource(const AssetMeshes& source);
  ~RaySource();
  RaySource(const RaySource&) = delete;
  RaySource& operator=(const RaySource&) = delete;

  // The hit on `surface` nearest to `origin` along the line through it with unit `direction`,
  // within `reach` both ways, on a surface that faces the direction's side (its interpolated
  // vertex normal has a positive component along `direction`: a surface seen from its back is
  // passed through); ahead wins a tie with behind.
  SourceHit nearestAlong(int surface, const std::array<float, 3>& origin, const std::array<float, 3>& direction,
                         float reach) const;

  // nearestAlong for up to kPacket queries at once, traced together as one Embree packet
  // (neighbouring texels' rays run alike, and a packet walks the tree once for all of them).
  // Query i: surface[i], origin[i], direction[i]; count <= kPacket. A query's answer may differ
  // from nearestAlong's in the last bits of its distance (the packet's arithmetic), never with
  // the thread count.
  static constexpr int kPacket = 8;
  void nearestAlong(int count, const int* surface, const std::array<float, 3>* origin,
                    const std::array<float, 3>* direction, float reach, SourceHit* hits) const;

  // How many of `count` (<= kPacket) rays from `origin` (unit directions) meet either
  // surface within (start, reach], traced as one packet.
  int occludedCount(const std::array<float, 3>& origin, int count, const std::array<float, 3>* directions, float start,
                    float reach) const;

  // Half the bounding-box diagonal of both surfaces, world units.
  double radius() const;

 private:
  struct Scene;
  std::unique_ptr<Scene> scene_;
};

}  // namespace rockbake
