// Chart segmentation for the UV atlas (docs/textures.md): each triangle of a surface is given
// a chart, so that every chart is connected, near-developable (every triangle's smoothed normal
// within kMaxChartCos of the chart's mean normal) and compact, and charts meet where seams hide.
//
// Variational shape approximation (Cohen-Steiner, Alliez, Desbrun, "Variational Shape
// Approximation", SIGGRAPH 2004) with a geodesic growth: charts grow from seeds by Dijkstra
// over the triangles' adjacency, a step costing the distance between the triangles' centroids,
// dearer across an edge where a seam hides (concave rock, the curvature attribute below ½;
// rock under colluvium; a crease, the triangles 30° … 75° apart) and dearer the further the
// triangle's normal turns from the chart's. So fronts meet, and seams lie, in concavities,
// under colluvium and on creases. Normals are smoothed over 2 % of the bounding-box diagonal
// first, so the detail's grain does not cut charts. Lloyd iterations move each seed to its
// chart's innermost triangle and its normal to the chart's mean; triangles no chart may take
// start charts of their own. Then neighbouring charts merge while the cone holds (smallest
// first, across the longest visible seam), a triangle that juts into another chart joins it,
// and a chart in pieces becomes one chart per piece.
#pragma once

#include <cstdint>
#include <vector>

#include "core/surface_mesh.h"

namespace rockbake {

// cos of the widest angle between a triangle's normal and its chart's mean normal.
inline constexpr double kMaxChartCos = 0.17;  // 80°

// A chart index per triangle, 0 … charts − 1, numbered in order of their lowest triangle.
// Deterministic. Triangles only; attributes are used where present.
std::vector<std::uint32_t> segmentCharts(const SurfaceMesh& mesh);

}  // namespace rockbake
