// Chart packing for the UV atlas (docs/textures.md): every chart turned to its smallest
// bounding rectangle (rotating calipers over its convex hull, landscape), scaled by one
// texel density for the whole atlas, and packed with stb_rect_pack (skyline) into a square
// map of `size` texels, each chart's rectangle `padding` + 1 texels larger than the chart,
// so at least `padding` empty texel centres lie between any two charts. The density is the
// largest a bisection finds that packs every chart.
#pragma once

#include <array>
#include <vector>

namespace rockbake {

// `charts`: each chart's uv in world units, counter-clockwise as the surface. On return, atlas
// uv in [0, 1] (glTF's convention: v down; counter-clockwise seen with v up). Returns the texel
// density, texels per world unit (0 when there is nothing to pack).
// Throws std::runtime_error if the charts cannot be packed at any density (more charts than
// texels with their gutters).
double packCharts(std::vector<std::vector<std::array<double, 2>>>& charts, int size, int padding);

}  // namespace rockbake
