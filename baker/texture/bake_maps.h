// The maps of one LOD (docs/textures.md), each made from the LOD's texel hits on the bake
// source (trace_texels.h), one map at a time, and dilated into the gutters and the empty
// atlas (dilate_texels.h). A texel whose rays missed the source takes the LOD's own values
// there (its normal, colour and attributes; open occlusion; height 0). Every map is a pure
// function of its inputs, TBB-parallel over rows, so it is byte-identical at any thread count.
//   normal      RGB 16-bit: the source's interpolated normal in the LOD's tangent frame at the
//               texel, encoded as glTF decodes it: a client rebuilds n = normalize(x·T + y·B
//               + z·N) from the interpolated, normalised vertex tangent T, bitangent B =
//               cross(N, T)·w and normal N (tangents.h), so (x, y, z) is that frame's inverse
//               applied to the source normal, normalised, stored as (c + 1) / 2 (OpenGL, +Y up)
//   base colour RGB 8-bit sRGB: the source's interpolated palette colour times the rock's
//               look at the hit (rock_look.h)
//   ORM         RGB 8-bit linear: R occlusion (ambient_occlusion.h, per LOD vertex, interpolated),
//               G roughness (rock_look.h; weatheredRoughness where the source has a look), B metal 0
//   height      1 channel float: the signed distance from the LOD to the source along the
//               LOD's normal, world units (positive outwards); LOD0's is the film displacement
//   history     RGBA 8-bit linear: the look's exposure age, stain and varnish, moisture, dust
//   mask        RGBA 8-bit linear: durability normalised over the asset's range (0 on
//               colluvium), colluvium coverage, curvature (exposure, ½ flat): COLOR_1's; and the
//               ground contact (GroundMask; COLOR_1's alpha is the altitude)
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "core/surface_mesh.h"
#include "core/vec3.h"
#include "mesh/ground_contact.h"
#include "texture/rasterize_uv.h"
#include "texture/rock_look.h"
#include "texture/trace_texels.h"

namespace rockbake {

// A square map, row-major, row 0 at v = 0, `channels` values a texel; or a band of its rows,
// first_row onwards (pixels.size() / (size · channels) of them).
template <class T>
struct TextureImage {
  int size = 0;
  int channels = 0;
  std::vector<T> pixels;
  int first_row = 0;
};

// What every map of one LOD reads. `lod` has uvs and normals (and tangents for the normal
// map); `texels` is rasterised from it and dilated; `hits` traced from it; `source` is the
// bake source.
struct LodBake {
  const AssetMeshes* lod = nullptr;
  const TexelMap* texels = nullptr;
  const TexelHits* hits = nullptr;
  const AssetMeshes* source = nullptr;
  // The rows to make, [first_row, last_row) (last_row −1: to the end): a map made in bands
  // holds one band at a time; its values are the whole map's, byte for byte.
  int first_row = 0;
  int last_row = -1;
};

// Tangent-space normals, 16-bit: OpenGL's convention (+Y, glTF's), or DirectX's (green inverted).
TextureImage<std::uint16_t> bakeNormalMap(const LodBake& bake, bool directx = false);
TextureImage<std::uint8_t> bakeBaseColor(const LodBake& bake, const RockLook& look);
// `occlusion`: vertexOcclusion of bake.lod.
TextureImage<std::uint8_t> bakeOrm(const LodBake& bake, const std::array<std::vector<float>, 2>& occlusion,
                                   const RockLook& look);
TextureImage<float> bakeHeight(const LodBake& bake);
// The mask's alpha: how close a point is to where the asset meets the ground (mesh/ground_contact.h),
// 1 on the contact, 0 from kGroundFeather voxels away (smoothstep in the 3-D distance), for engines
// blending terrain into the rock's foot. Empty (contact null): 0 everywhere.
inline constexpr double kGroundFeather = 3.0;
struct GroundMask {
  std::shared_ptr<const PlaneDistance> contact;
  double ground = 0.0;   // the ground plane's z
  double feather = 0.0;  // world units
  double at(const Vec3d& p) const;
};
// From the bake source's rims on the plane `ground` (none: empty); `voxel` the grid's h.
GroundMask groundMask(const AssetMeshes& source, std::optional<double> ground, double voxel);

// R durability (normalised), G colluvium coverage, B curvature, A ground contact (GroundMask).
TextureImage<std::uint8_t> bakeMask(const LodBake& bake, const RockLook& look, const GroundMask& ground);
// The source's look (SurfaceMesh::look; mesh/surface_look.h): R exposure age, G stain and varnish,
// B moisture, A dust, each 0..1, linear. Texels whose mesh has no look are 0.
TextureImage<std::uint8_t> bakeHistory(const LodBake& bake);

}  // namespace rockbake
