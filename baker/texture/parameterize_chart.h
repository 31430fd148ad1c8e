// One chart's parameterisation for the UV atlas (docs/textures.md): least squares conformal
// maps (Lévy, Petitjean, Ray, Maillot, "Least Squares Conformal Maps for Automatic Texture
// Atlas Generation", SIGGRAPH 2002), solved with Eigen's sparse Cholesky, two boundary
// vertices far apart pinned; then scaled so the chart's area in the plane equals its area on
// the surface (world units), and checked.
//
// A chart is usable when it is a topological disk (one boundary loop, Euler characteristic 1),
// no triangle is turned over, its boundary does not cross itself (with no fold, the map is
// then one-to-one), and its texel density is even: at most 10 % of its area has a linear scale
// outside [½, 2] of the chart's mean. A vertex the chart touches in two fans (a pinch) is two
// chart vertices. A chart that fails is split (splitChart) and both
// halves parameterised again; a single triangle never fails.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/surface_mesh.h"
#include "geometry/edge_table.h"

namespace rockbake {

enum class ChartStatus { Ok, NotDisk, Folded, SelfOverlapping, Stretched };

struct ChartUv {
  ChartStatus status = ChartStatus::Ok;
  // The chart's vertices, in first use over its triangles: the mesh vertex each copies (a
  // vertex the chart touches in two separate fans gives two chart vertices).
  std::vector<std::uint32_t> vertices;
  std::vector<std::array<std::uint32_t, 3>> corners;  // per chart triangle, in order: its chart vertices
  std::vector<std::array<double, 2>> uv;              // per chart vertex, world units, counter-clockwise as the surface
};

// `triangles`: a connected set of the mesh's triangles. Deterministic.
ChartUv parameterizeChart(const SurfaceMesh& mesh, const std::vector<std::uint32_t>& triangles);

// Splits a chart of two or more triangles in two connected halves, grown from two triangles
// far apart (breadth-first, then nearest by centroid distance). `edges`: the mesh's edge
// table (geometry/edge_table.h). Deterministic.
std::array<std::vector<std::uint32_t>, 2> splitChart(const SurfaceMesh& mesh, const EdgeTable& edges,
                                                     const std::vector<std::uint32_t>& triangles);

}  // namespace rockbake
