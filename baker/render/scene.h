// POV-Ray scenes for a baked asset (docs/rendering.md): the mesh2 include and a filled
// template.
//
// Frames. The baker's world is right-handed, z up (SurfaceMesh). POV-Ray is
// left-handed, y up. A world point (x, y, z) is written as the POV-Ray vector
// <x, z, y>: swapping y and z is a reflection, and so is the change from a
// right- to a left-handed system, so the two cancel and the picture is not
// mirrored (a rock seen from -y with +x to the right looks the same in both).
// Every vector the baker writes into a scene (vertices, normals, camera, the
// asset's centre) goes through worldToPov(); {{GROUND_Z}} is the world z of
// the ground, which is POV-Ray's y.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <string_view>

#include "core/clast_set.h"
#include "core/surface_mesh.h"

namespace rockbake {

using Vec3 = std::array<double, 3>;

Vec3 worldToPov(const Vec3& world);

// A perspective camera, in world coordinates (z up). angle_deg is the
// horizontal field of view, as POV-Ray's `angle`.
struct CameraSetup {
  Vec3 location{};
  Vec3 look_at{};
  double angle_deg = 40.0;
};

// What framing needs to know about an asset: its world bounding box and the
// radius of its bounding sphere about the box's centre (the farthest vertex).
struct AssetFrame {
  Vec3 bounds_min{}, bounds_max{};
  double radius = 0;
  Vec3 centre() const;
};
AssetFrame assetFrame(const AssetMeshes& meshes);
// The frame recorded in a mesh include written by writeMeshInclude (its
// "// rockbake-frame:" line), to re-render without the meshes.
AssetFrame readAssetFrame(const std::filesystem::path& mesh_include);

// Frames the asset for a width × height image, seen from 20° above the
// horizon at azimuth -60° + turntable_deg around the world z axis through the
// bounding box's centre (0° = the +x side, -90° = the -y side): the camera
// backs off just far enough that the bounding sphere (radius: the farthest
// vertex) fits the narrower field of view, or that every bounding-box corner
// projects inside 92 % of the horizontal and vertical fields of view,
// whichever is nearer. The vertical field follows from the horizontal one and
// the aspect ratio. The camera stays outside the bounding sphere.
CameraSetup frameCamera(const AssetFrame& asset, int width, int height, double turntable_deg = 0.0,
                        double angle_deg = 40.0);
CameraSetup frameCamera(const AssetMeshes& meshes, int width, int height, double turntable_deg = 0.0,
                        double angle_deg = 40.0);

// The texture set's LOD0 maps as a render reads them (docs/textures.md), file names relative
// to the asset folder, POV-Ray's working folder.
// Only the base colour: POV-Ray 3.7 has no tangent-space normal maps, and its image bump tilts
// normals along the pattern's own axes, not along each chart's frame in the atlas, so a bump
// from the height map crumples the surface (docs/rendering.md).
struct RenderMaps {
  std::string base_color;  // 8-bit sRGB PNG
  bool empty() const { return base_color.empty(); }
};

// Writes the mesh2 include (atomically): declares Rockbake_Rock and, when there
// is colluvium, Rockbake_Colluvium (objects), and Rockbake_Has_Colluvium (0/1).
// Vertex colours go into a texture_list, one texture per distinct colour
// (the linear colour rounded to 1/4096, varied between Rockbake_Dark and
// Rockbake_Light times itself by the pigment Rockbake_Rock_Grain /
// Rockbake_Colluvium_Grain, bumped by Rockbake_Rock_Normal /
// Rockbake_Colluvium_Normal, finish Rockbake_Finish; a template may #declare
// each before the #include, the defaults give the flat colour); faces carry
// their three vertices' texture indices, so colours interpolate.
//
// With `maps` (the meshes then have uvs: the texture set's LOD0) the include also
// declares Rockbake_Has_Maps = 1 and, where a template sets Rockbake_Use_Maps to 1
// before the #include, gives both surfaces instead the one texture
// Rockbake_Mapped: the base colour through the uvs (`uv_mapping` image_map,
// `gamma srgb`), finish Rockbake_Finish. Without maps the
// include is as above, whatever the template sets.
//
// With `clasts` (stones on the apron) the colluvium's surface is declared as
// Rockbake_Colluvium_Apron and Rockbake_Colluvium is the union of it and the stones, placed and
// merged into one mesh2 Rockbake_Clasts in vertex colours with the rock's grain and bump.
void writeMeshInclude(const AssetMeshes& meshes, const std::filesystem::path& file, const RenderMaps& maps = {},
                      const ClastSet* clasts = nullptr);

struct SceneFrame {
  int frame = 0;   // 0-based
  int frames = 1;  // frames in the turntable (1 for a still)
  double turntable_deg = 0.0;
  bool lookdev = false;  // {{LOOKDEV}}: the look-dev set in frame (render.turntable.lookdev)
};

// The values for every placeholder documented in render_templates/README.md;
// {{SEED_OFFSET}} derives from `seed` (the preset's).
std::map<std::string, std::string> scenePlaceholders(const AssetFrame& asset, const CameraSetup& camera,
                                                     const CameraSetup& home_camera, const SceneFrame& frame,
                                                     const std::string& mesh_include, std::uint64_t seed = 0);

// render_templates/<name>.pov; std::runtime_error listing the templates there
// when it does not exist.
std::filesystem::path findTemplate(const std::filesystem::path& template_dir, const std::string& name);

// Replaces every {{NAME}} in `text`. A placeholder with no value is an error
// naming it, the template and the line (so a typo in a template is caught
// before POV-Ray runs).
std::string fillTemplate(std::string_view text, const std::map<std::string, std::string>& values,
                         const std::string& template_label);

// Reads the template, fills it and writes `scene_file` atomically.
void writeScene(const std::filesystem::path& template_file, const std::map<std::string, std::string>& values,
                const std::filesystem::path& scene_file);

}  // namespace rockbake
