#include "collision/point_hull.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>

#include <libqhullcpp/Qhull.h>
#include <libqhullcpp/QhullError.h>
#include <libqhullcpp/QhullFacetList.h>
#include <libqhullcpp/QhullVertexSet.h>

namespace rockbake {
namespace {
std::vector<double> flatten(const std::vector<Vec3d>& points) {
  std::vector<double> coords;
  coords.reserve(3 * points.size());
  for (const Vec3d& p : points) coords.insert(coords.end(), p.begin(), p.end());
  return coords;
}

// Runs Qhull, turning its errors into std::runtime_error. Qhull keeps warnings
// as messages it would print to stderr when destroyed; they are dropped.
// Qhull reads `coords` in place, to the end: they must outlive `qhull`.
void runQhull(orgQhull::Qhull& qhull, int dimension, const std::vector<double>& coords, const char* options) {
  try {
    qhull.runQhull("", dimension, int(coords.size() / std::size_t(dimension)), coords.data(), options);
  } catch (const std::exception& e) {
    qhull.clearQhullMessage();
    throw std::runtime_error(std::string("Qhull failed: ") + e.what());
  }
  qhull.clearQhullMessage();
}

Vec3d vertexPoint(const orgQhull::QhullVertex& v) {
  const double* c = v.point().coordinates();
  return {c[0], c[1], c[2]};
}

}  // namespace

PointHull hullOfPoints(const std::vector<Vec3d>& points) {
  const std::vector<double> coords = flatten(points);
  orgQhull::Qhull qhull;
  runQhull(qhull, 3, coords, "");
  PointHull hull;
  for (const orgQhull::QhullVertex& v : qhull.vertexList()) hull.vertices.push_back(vertexPoint(v));
  std::sort(hull.vertices.begin(), hull.vertices.end());
  for (const orgQhull::QhullFacet& f : qhull.facetList()) {
    const double* n = f.hyperplane().coordinates();
    hull.planes.push_back({{n[0], n[1], n[2]}, -f.hyperplane().offset()});
  }
  hull.volume = qhull.volume();
  return hull;
}

TriangulatedHull triangulateHull(const std::vector<Vec3d>& points) {
  const std::vector<double> coords = flatten(points);
  orgQhull::Qhull qhull;
  runQhull(qhull, 3, coords, "Qt");
  // The kept vertices in input order, numbered from 0.
  std::vector<int> ids;
  for (const orgQhull::QhullVertex& v : qhull.vertexList()) ids.push_back(v.point().id());
  std::sort(ids.begin(), ids.end());
  std::vector<std::int64_t> index_of(points.size(), -1);
  TriangulatedHull hull;
  for (const int id : ids) {
    index_of[std::size_t(id)] = std::int64_t(hull.vertices.size());
    hull.vertices.push_back(points[std::size_t(id)]);
  }
  for (const orgQhull::QhullFacet& f : qhull.facetList()) {
    std::array<std::uint32_t, 3> t{};
    int corner = 0;
    for (const orgQhull::QhullVertex& v : f.vertices())
      t[std::size_t(corner++)] = std::uint32_t(index_of[std::size_t(v.point().id())]);
    if (corner != 3) throw std::runtime_error("Qhull gave a facet of " + std::to_string(corner) + " vertices with Qt");
    const double* n = f.hyperplane().coordinates();
    const Vec3d& a = hull.vertices[t[0]];
    if (dot(cross(sub(hull.vertices[t[1]], a), sub(hull.vertices[t[2]], a)), Vec3d{n[0], n[1], n[2]}) < 0)
      std::swap(t[1], t[2]);
    hull.triangles.push_back(t);
  }
  return hull;
}

Polytope intersectHalfSpaces(const std::vector<HullPlane>& planes, const Vec3d& interior) {
  // Qhull takes a half-space as (normal, offset) with normal · x + offset <= 0.
  std::vector<double> coords;
  coords.reserve(4 * planes.size());
  for (const HullPlane& p : planes) coords.insert(coords.end(), {p.normal[0], p.normal[1], p.normal[2], -p.offset});
  orgQhull::Qhull qhull;
  qhull.setFeasiblePoint(orgQhull::Coordinates(std::vector<double>(interior.begin(), interior.end())));
  runQhull(qhull, 4, coords, "H");
  // Each facet of the dual hull is one vertex of the intersection (Qhull's
  // option Fp): interior - normal / offset; a facet with offset >= 0 is a
  // direction in which the intersection is unbounded. The facet's vertices
  // are the half-spaces whose planes meet there.
  Polytope polytope;
  polytope.faces.resize(planes.size());
  for (const orgQhull::QhullFacet& f : qhull.facetList()) {
    const double offset = f.hyperplane().offset();
    if (offset > -1e-12) throw std::runtime_error("the half-space intersection is unbounded");
    const double* n = f.hyperplane().coordinates();
    const auto index = std::uint32_t(polytope.vertices.size());
    polytope.vertices.push_back(
        {interior[0] - n[0] / offset, interior[1] - n[1] / offset, interior[2] - n[2] / offset});
    for (const orgQhull::QhullVertex& v : f.vertices()) polytope.faces[std::size_t(v.point().id())].push_back(index);
  }
  // Each face's vertices in order around its plane's normal.
  for (std::size_t k = 0; k < planes.size(); ++k) {
    std::vector<std::uint32_t>& face = polytope.faces[k];
    if (face.size() < 3) continue;
    const Vec3d& n = planes[k].normal;
    Vec3d centre{};
    for (const std::uint32_t v : face) centre = add(centre, polytope.vertices[v]);
    centre = scale(centre, 1.0 / double(face.size()));
    const Vec3d u = std::abs(n[0]) < 0.9 ? cross(n, Vec3d{1, 0, 0}) : cross(n, Vec3d{0, 1, 0});
    const Vec3d w = cross(n, u);
    std::vector<std::pair<double, std::uint32_t>> around;
    for (const std::uint32_t v : face) {
      const Vec3d d = sub(polytope.vertices[v], centre);
      around.push_back({std::atan2(dot(d, w), dot(d, u)), v});
    }
    std::sort(around.begin(), around.end());
    for (std::size_t i = 0; i < face.size(); ++i) face[i] = around[i].second;
  }
  return polytope;
}

}  // namespace rockbake
