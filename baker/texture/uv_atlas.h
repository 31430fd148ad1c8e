// The UV atlas (docs/textures.md): both surfaces of an asset unwrapped into one square map.
// Each surface is cut into charts (segment_charts.h: near-developable, seams along creases,
// in concavities and under colluvium), each chart flattened with LSCM and split until it is a
// one-to-one, evenly scaled disk (parameterize_chart.h), and all charts scaled to one texel
// density and packed with `params.padding`-texel gutters into `params.size`² texels
// (pack_charts.h). Closed surfaces of any genus, many components and slivers are handled:
// a chart that fails is split, down to single triangles.
//
// The result holds the same triangles in the same order, with vertices split along the seams
// (each copy keeps its position, normal, attributes and colour) and `uvs` in [0, 1]; tangents
// are left empty (tangents.h fills them). Deterministic: a pure function of the meshes, `size`
// and `padding` (the thread count does not matter).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/surface_mesh.h"

namespace rockbake {

struct UvAtlas {
  AssetMeshes meshes;            // rock and colluvium with uvs (bounds and durability range as given)
  std::size_t charts = 0;        // over both surfaces
  double texels_per_unit = 0.0;  // texel density, texels per world unit (0 when there is no surface)
  // Per surface: each vertex's in the input mesh (its copies along the seams share it).
  std::array<std::vector<std::uint32_t>, 2> source_vertex;
};

// Per surface (rock, colluvium), per triangle: 1 where the surface is hidden, no ray from outside
// reaching it (docs/textures.md, "Hidden surface"; texture_set.h finds it). A chart at least
// kHiddenShare of whose area is hidden is packed at kHiddenDensity of the others' density (a
// sixteenth of the texels): the visible surface gets the rest.
using HiddenTriangles = std::array<std::vector<std::uint8_t>, 2>;
inline constexpr double kHiddenDensity = 0.25;
inline constexpr double kHiddenShare = 0.9;

// Triangle-only meshes (quads are ignored). `size`: the map's width and height, texels (1 …
// 8192); `padding`: empty texels between charts (0 … 64); `hidden`: the hidden triangles (above),
// or none. Throws std::invalid_argument on a size or padding outside those ranges and
// ChartsDoNotFit (texture_params.h) when the charts do not fit the map at any density.
UvAtlas buildUvAtlas(const AssetMeshes& meshes, int size, int padding, const HiddenTriangles* hidden = nullptr);

// The texel density of meshes with uvs in a `size`² map: the area-weighted median over the
// triangles of sqrt(texel area / surface area), texels per world unit (0 without area).
double texelDensity(const AssetMeshes& meshes, int size);

// The share of the unit uv square the triangles of meshes with uvs cover, 0 … 1 (charts do not
// overlap): what the gutters and the packing leave the surface.
double uvCoverage(const AssetMeshes& meshes);

}  // namespace rockbake
