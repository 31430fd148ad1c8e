// Chart packing for the UV atlas (docs/textures.md §1): the "Tetris" packing of Lévy, Petitjean,
// Ray and Maillot ("Least Squares Conformal Maps for Automatic Texture Atlas Generation",
// SIGGRAPH 2002, §6), written from the paper, with the holes it leaves filled: each chart,
// turned to its smallest bounding rectangle (rotating calipers over its convex hull) and tried
// at each quarter turn, is rasterised at the atlas's texel density (the texels whose centre its
// triangles cover, as runs of rows per column) and grown by half the gutter; charts go in by
// decreasing bounding-rectangle area, each dropped to the lowest row where it meets no texel
// taken so far, in a hole beneath earlier charts as well as on top of them. So a chart's jagged
// edge nests into its neighbours' and small charts fill the gaps big ones leave. Any two charts
// end up at least `padding` empty texels apart (between texel centres they cover), and
// `padding` / 2 from the map's edges.
//
// The search keeps, per column of the map, its taken rows as bits and its free gaps as a list,
// with the lowest gap of each length: a chart tried at a column starts above every gap too
// short for its runs there and is lifted past a taken texel straight to the next gap long
// enough, so its cost follows the gaps it could fit in, not every run taken beneath it.
//
// The density is the largest a few rounds of packing find whose charts fit `size` texels down
// (the width is the map's): each round scales it by the square root of the height it missed by
// (or, when a packing outgrows the map, of the share of texels it placed), then moves between
// the densities that fit and failed, towards where the last fit's height says the map is
// full, until the charts fill at least 98 % of the map's height.
// Deterministic.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace rockbake {

struct PackChart {
  std::vector<std::array<double, 2>> uv;                // per chart vertex: world units in, atlas uv [0, 1] out
  std::vector<std::array<std::uint32_t, 3>> triangles;  // chart vertices, counter-clockwise
};

// What a packing did, over all its rounds: the search's work in counts, not seconds.
struct PackWork {
  std::uint64_t charts = 0;       // charts placed
  std::uint64_t positions = 0;    // positions (column and turn) a chart was tried at
  std::uint64_t lifts = 0;        // times a footprint met a taken texel and was lifted
  std::uint64_t gaps_passed = 0;  // free gaps a lift looked at above the one it started in
};

// Atlas uv follow glTF (v down; counter-clockwise seen with v up). Returns the texel density,
// texels per world unit (0 when there is nothing to pack); `work`, when given, receives the
// counts. Throws ChartsDoNotFit (texture_params.h) if the charts fit at no density (more charts than texels
// with their gutters).
double packCharts(std::vector<PackChart>& charts, int size, int padding, PackWork* work = nullptr);

// The convex hull of points in the plane (Andrew's monotone chain): its corners counter-clockwise
// from the lowest (x, y), each once; fewer than three points as they are, sorted, without repeats.
std::vector<std::array<double, 2>> convexHull(std::vector<std::array<double, 2>> points);

// The area of the convex hull of points in the plane (0 for fewer than three points apart).
double convexHullArea(const std::vector<std::array<double, 2>>& points);

}  // namespace rockbake
