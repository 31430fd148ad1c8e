// Convex hulls and half-space intersections through Qhull (Barber, Dobkin and
// Huhdanpaa, "The Quickhull algorithm for convex hulls", ACM TOMS 22(4), 1996),
// in 3-D, double precision, in whatever frame the caller's points are
// (the collision stage works in voxel index space, where voxel corners are
// whole numbers). Deterministic: the same points in the same order give the
// same hull. Thread-safe (each call runs its own reentrant Qhull).
// Every function throws std::runtime_error, with Qhull's message, when Qhull
// fails (fewer than four points not on one plane, an empty intersection).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/vec3.h"

namespace rockbake {

// A supporting plane: every point of the hull has normal · x <= offset.
struct HullPlane {
  Vec3d normal;  // unit length, outward
  double offset;
};

struct PointHull {
  std::vector<Vec3d> vertices;    // the hull's vertices, sorted lexicographically
  std::vector<HullPlane> planes;  // one per facet, coplanar facets merged (within Qhull's rounding of `vertices`)
  double volume = 0.0;
};

// The convex hull of `points` (duplicates allowed).
PointHull hullOfPoints(const std::vector<Vec3d>& points);

// The hull of `points` as triangles: the vertices Qhull keeps (points inside
// or within rounding of a face are dropped) and triangles indexing them,
// counter-clockwise seen from outside.
struct TriangulatedHull {
  std::vector<Vec3d> vertices;
  std::vector<std::array<std::uint32_t, 3>> triangles;
};
TriangulatedHull triangulateHull(const std::vector<Vec3d>& points);

// The bounded polytope ∩ {x : normal · x <= offset}, through Qhull's
// half-space intersection; `interior` must lie strictly inside every
// half-space. A vertex where more than three planes meet comes once.
struct Polytope {
  std::vector<Vec3d> vertices;
  // Per plane, the vertices on it, counter-clockwise seen from outside; fewer
  // than three where the plane only touches the polytope (or misses it).
  std::vector<std::vector<std::uint32_t>> faces;
};
Polytope intersectHalfSpaces(const std::vector<HullPlane>& planes, const Vec3d& interior);

}  // namespace rockbake
