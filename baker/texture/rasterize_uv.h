// Rasterising in UV space (docs/textures.md): which triangle's interior holds each texel's
// centre. Texel (x, y) is the square [x, x + 1] × [y, y + 1] in texel units, u · size across
// and v · size down, its centre at (x + ½, y + ½). Coordinates are snapped to 1/256 texel and
// tested with exact integer edge functions; a centre on an edge two triangles share goes to
// exactly one of them (the top-left rule), so a chart's texels are claimed once each.
// Triangles are visited in order (rock's, then colluvium's); where a texel centre lies in two
// triangles (overlapping charts), the first keeps it and the texel counts as contested.
// Parallel over bands of rows; the result does not depend on the thread count.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/surface_mesh.h"

namespace rockbake {

inline constexpr std::uint32_t kEmptyTexel = 0xffffffffu;
inline constexpr std::uint32_t kDilatedTexel = 0x80000000u;  // dilate_texels.h: flag | the texel copied

struct TexelMap {
  int size = 0;
  // Row-major, row 0 at v = 0: the triangle holding the texel centre, numbered over the
  // surfaces in order (rock's triangles, then colluvium's), or kEmptyTexel.
  std::vector<std::uint32_t> texels;
  std::size_t covered = 0;    // texels with a triangle
  std::size_t contested = 0;  // of those, texels whose centre lies inside two or more triangles
};

// Meshes with uvs (an empty surface is skipped). Throws std::invalid_argument if a non-empty
// surface has no uv per vertex or size is outside 1..8192.
TexelMap rasterizeUv(const AssetMeshes& meshes, int size);

// The triangle numbered `index` in a TexelMap: its surface (0 rock, 1 colluvium) and its
// index there.
struct TriangleRef {
  int surface;
  std::uint32_t triangle;
};
inline TriangleRef triangleRef(const AssetMeshes& meshes, std::uint32_t index) {
  const auto rock = std::uint32_t(meshes.rock.triangles.size());
  return index < rock ? TriangleRef{0, index} : TriangleRef{1, index - rock};
}

}  // namespace rockbake
