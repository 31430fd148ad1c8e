#include "collision/collision_hulls.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <tbb/parallel_for.h>

#include "collision/air_count.h"
#include "collision/merge_parts.h"
#include "collision/reduce_hull.h"
#include "collision/voxel_parts.h"

namespace rockbake {
namespace {
// About how many parts the material is cut into (docs/collision.md, "Parts"),
// whatever the resolution: enough that a part rarely spans a concavity, few
// enough that merging them stays well within a second. Blocks are about 60 %
// full on weathered rock.
constexpr double kParts = 100;
constexpr double kBlockFill = 0.6;
// Merges below max_hulls are made while together they add at most this
// fraction of the material's voxels in air (docs/collision.md, "Merging").
constexpr double kFreeMergeFraction = 0.02;

void checkParams(const CollisionParams& p) {
  if (p.max_hulls < 1 || p.max_hulls > CollisionParams::kMaxHulls)
    throw std::invalid_argument("collision.max_hulls " + std::to_string(p.max_hulls) + " outside 1.." +
                                std::to_string(CollisionParams::kMaxHulls));
  if (p.max_vertices < CollisionParams::kMinVertices || p.max_vertices > CollisionParams::kMaxVertices)
    throw std::invalid_argument("collision.max_vertices " + std::to_string(p.max_vertices) + " outside " +
                                std::to_string(CollisionParams::kMinVertices) + ".." +
                                std::to_string(CollisionParams::kMaxVertices));
}

int blockSize(const VoxelBounds& bounds) {
  return std::clamp(int(std::lround(std::cbrt(double(bounds.voxels) / (kParts * kBlockFill)))), 2, 40);
}

// A piece's hull with its vertices capped, from voxel index space to world units.
ConvexHull finishHull(const MergedPiece& piece, int max_vertices, const GridLayout& layout) {
  const TriangulatedHull t = triangulateHull(reduceHull(piece.hull, max_vertices).vertices);
  ConvexHull hull;
  hull.voxels = piece.voxels;
  hull.triangles = t.triangles;
  hull.positions.reserve(t.vertices.size());
  for (const Vec3d& v : t.vertices) hull.positions.push_back(add(layout.origin, scale(v, layout.h)));
  for (const auto& tri : hull.triangles)
    hull.volume += dot(hull.positions[tri[0]], cross(hull.positions[tri[1]], hull.positions[tri[2]])) / 6.0;
  return hull;
}

}  // namespace

ConvexHull stoneHull(const std::vector<Vec3d>& points, int max_vertices) {
  const TriangulatedHull t = triangulateHull(reduceHull(hullOfPoints(points), max_vertices).vertices);
  ConvexHull hull;
  hull.positions = t.vertices;
  hull.triangles = t.triangles;
  // The volume about the hull's first vertex: the stones lie far from the origin for their size.
  const Vec3d o = hull.positions.empty() ? Vec3d{} : hull.positions[0];
  for (const auto& tri : hull.triangles)
    hull.volume +=
        dot(sub(hull.positions[tri[0]], o), cross(sub(hull.positions[tri[1]], o), sub(hull.positions[tri[2]], o))) /
        6.0;
  return hull;
}

std::vector<ConvexHull> hullVoxels(const VoxelRock& rock, Material material, const CollisionParams& params) {
  checkParams(params);
  const VoxelBounds bounds = materialBounds(rock, material);
  if (bounds.voxels == 0) return {};
  const AirCounter air(rock, bounds);
  const VoxelParts parts = splitIntoParts(rock, material, bounds, blockSize(bounds), air);
  const std::vector<MergedPiece> pieces =
      mergeParts(parts, air, {std::size_t(params.max_hulls), kFreeMergeFraction, params.max_vertices});
  std::vector<ConvexHull> hulls(pieces.size());
  tbb::parallel_for(std::size_t(0), pieces.size(),
                    [&](std::size_t i) { hulls[i] = finishHull(pieces[i], params.max_vertices, rock.layout); });
  std::sort(hulls.begin(), hulls.end(), [](const ConvexHull& a, const ConvexHull& b) {
    return a.volume != b.volume ? a.volume > b.volume : a.positions < b.positions;
  });
  return hulls;
}

CollisionHulls buildCollisionHulls(const VoxelRock& rock, const CollisionParams& params) {
  CollisionHulls hulls;
  hulls.rock = hullVoxels(rock, Material::Rock, params);
  if (params.colluvium) hulls.colluvium = hullVoxels(rock, Material::Colluvium, params);
  return hulls;
}

}  // namespace rockbake
