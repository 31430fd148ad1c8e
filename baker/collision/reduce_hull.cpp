#include "collision/reduce_hull.h"

#include <algorithm>
#include <cstddef>
#include <stdexcept>
#include <string>

namespace rockbake {
namespace {
// Planes tried, in order of the volume they cut off, before the search stops
// at the cap (each try is one half-space intersection).
constexpr std::size_t kAttemptsAtCap = 8;

// Signed volume of the tetrahedron (o, a, b, c), positive when a, b, c run
// counter-clockwise seen from outside.
double tetraVolume(const Vec3d& o, const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  return dot(sub(a, o), cross(sub(b, o), sub(c, o))) / 6.0;
}

// The volume of the polytope on the far side of the plane (normal · x >
// offset), given each vertex's height above it. Each face is clipped to that
// side; with the apex on the plane the cut face adds nothing, so the clipped
// faces' cones from the apex sum to the volume.
double volumeBeyond(const Polytope& p, const std::vector<double>& height, const HullPlane& plane) {
  const Vec3d apex = scale(plane.normal, plane.offset);  // on the plane (unit normal)
  double volume = 0.0;
  std::vector<Vec3d> corners;
  for (const std::vector<std::uint32_t>& face : p.faces) {
    if (face.size() < 3 || std::none_of(face.begin(), face.end(), [&](std::uint32_t v) { return height[v] > 0; }))
      continue;
    // Sutherland–Hodgman against the plane.
    corners.clear();
    for (std::size_t i = 0; i < face.size(); ++i) {
      const std::uint32_t a = face[i], b = face[(i + 1) % face.size()];
      if (height[a] > 0) corners.push_back(p.vertices[a]);
      if ((height[a] > 0) != (height[b] > 0))
        corners.push_back(
            add(p.vertices[a], scale(sub(p.vertices[b], p.vertices[a]), height[a] / (height[a] - height[b]))));
    }
    for (std::size_t k = 1; k + 1 < corners.size(); ++k)
      volume += tetraVolume(apex, corners[0], corners[k], corners[k + 1]);
  }
  return volume;
}

}  // namespace

CappedHull reduceHull(const PointHull& hull, int max_vertices) {
  if (max_vertices < 8)
    throw std::invalid_argument("reduceHull: max_vertices " + std::to_string(max_vertices) + " < 8");
  if (hull.vertices.size() <= std::size_t(max_vertices)) return {hull.vertices, hull.planes};

  Vec3d lo = hull.vertices.front(), hi = lo, centre{};
  for (const Vec3d& v : hull.vertices) {
    for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], v[a]), hi[a] = std::max(hi[a], v[a]);
    centre = add(centre, v);
  }
  centre = scale(centre, 1.0 / double(hull.vertices.size()));  // strictly inside: the hull has volume
  double extent = 0.0;
  for (int a = 0; a < 3; ++a) extent = std::max(extent, hi[a] - lo[a]);
  const double tolerance = 1e-9 * extent;

  // Qhull's merged facets hold the vertices within its rounding; each offset
  // is made tight on them, so that every half-space holds the whole hull.
  std::vector<HullPlane> facets = hull.planes;
  for (HullPlane& f : facets)
    for (const Vec3d& v : hull.vertices) f.offset = std::max(f.offset, dot(f.normal, v));

  std::vector<HullPlane> planes;  // the bounding box's, then the chosen facets'
  for (int a = 0; a < 3; ++a) {
    Vec3d n{};
    n[a] = 1.0;
    planes.push_back({n, hi[a]});
    n[a] = -1.0;
    planes.push_back({n, -lo[a]});
  }
  Polytope polytope = intersectHalfSpaces(planes, centre);
  std::vector<char> used(facets.size(), 0);
  std::vector<double> height;
  while (true) {
    // Each facet plane by the volume it would cut off the polytope.
    std::vector<std::pair<double, std::size_t>> cuts;
    for (std::size_t f = 0; f < facets.size(); ++f) {
      if (used[f]) continue;
      height.resize(polytope.vertices.size());
      bool beyond = false;
      for (std::size_t v = 0; v < height.size(); ++v) {
        height[v] = dot(facets[f].normal, polytope.vertices[v]) - facets[f].offset;
        beyond = beyond || height[v] > tolerance;
      }
      if (beyond) cuts.push_back({volumeBeyond(polytope, height, facets[f]), f});
    }
    std::sort(cuts.begin(), cuts.end(), [](const auto& a, const auto& b) {
      return a.first != b.first ? a.first > b.first : a.second < b.second;
    });
    bool added = false;
    for (std::size_t i = 0; i < cuts.size() && i < kAttemptsAtCap; ++i) {
      planes.push_back(facets[cuts[i].second]);
      Polytope next = intersectHalfSpaces(planes, centre);
      if (next.vertices.size() <= std::size_t(max_vertices)) {
        used[cuts[i].second] = 1;
        polytope = std::move(next);
        added = true;
        break;
      }
      planes.pop_back();
    }
    if (!added) break;
  }
  return {std::move(polytope.vertices), std::move(planes)};
}

}  // namespace rockbake
