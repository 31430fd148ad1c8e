// Chart packing for the UV atlas (docs/textures.md): the "Tetris" packing of Lévy, Petitjean,
// Ray and Maillot ("Least Squares Conformal Maps for Automatic Texture Atlas Generation",
// SIGGRAPH 2002, §6), written from the paper, with the holes it leaves filled: each chart,
// turned to its smallest bounding rectangle (rotating calipers over its convex hull) and tried
// at each quarter turn, is rasterised at the atlas's texel density (every texel its triangles
// touch, as runs of rows per column) and grown by half the gutter; charts go in by decreasing
// bounding-rectangle area, each dropped to the lowest row where it meets no texel taken so far,
// in a hole beneath earlier charts as well as on top of them. So a chart's jagged edge nests
// into its neighbours' and small charts fill the gaps big ones leave. Any two charts end up at
// least `padding` texels apart (between texel centres they cover), and `padding` / 2 from the
// map's edges.
//
// The density is the largest a few rounds of packing find whose charts fit `size` texels down
// (the width is the map's): each round scales it by the square root of the height it missed by
// (or, when a packing outgrows the map, of the share of texels it placed), then bisects, until
// the charts fill at least 98 % of the map's height.
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

// Atlas uv follow glTF (v down; counter-clockwise seen with v up). Returns the texel density,
// texels per world unit (0 when there is nothing to pack). Throws std::runtime_error if the
// charts fit at no density (more charts than texels with their gutters).
double packCharts(std::vector<PackChart>& charts, int size, int padding);

}  // namespace rockbake
