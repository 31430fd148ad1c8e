// The validated preset: plain data, the contract every later stage reads.
// docs/preset-reference.md. Lengths are world units, altitudes are normalised to [0, 1] from the
// ground (z = 0) to the top of grid.size, angles are degrees.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "core/error.h"
#include "core/vec3.h"

namespace rockbake {

struct GridParams {
  static constexpr int kMinResolution = 8, kMaxResolution = 2048;
  Vec3d size{4.0, 4.0, 6.0};  // simulation domain, world units, all > 0
  int resolution = 96;        // voxels along the longest side, kMinResolution..kMaxResolution
  bool ground = true;         // false: free-floating rock, rockfall off
};

// ---- initial shape (docs/model.md §8) ----
struct BoxShape {
  Vec3d size;
};
struct CylinderShape {
  double radius;
  double height;
};
struct SphereShape {
  double radius;
};
// An L-shaped block: two walls of thickness `wall` meeting at a right angle,
// footprint size[0] × size[1], height size[2]. The re-entrant corner opens
// towards +x +y.
struct InsideCornerShape {
  Vec3d size;
  double wall;
};
enum class ImageMode { Extrude, Revolve };
struct ImageShape {
  std::filesystem::path path;  // absolute (resolved against the preset's folder)
  ImageMode mode = ImageMode::Extrude;
  double height;  // extrude: extrusion height; revolve: height of the profile
};
// An artist's closed blockout (OBJ, PLY or STL), voxelized. File coordinates
// times `scale` are world units; placed like the other shapes by its bounding
// box (centre in x, y; base at z).
enum class UpAxis { Z, Y };
struct MeshShape {
  std::filesystem::path path;  // absolute (resolved against the preset's folder)
  double scale = 1.0;          // world units per file unit, > 0
  // The file's up axis: z (rockbake's, PLY's and most CAD's) or y (OBJ and glTF as DCCs write them,
  // rockbake's own OBJ export among them): a y-up file's (x, y, z) is the world's (x, −z, y).
  UpAxis up = UpAxis::Z;
};
using ShapeKind = std::variant<BoxShape, CylinderShape, SphereShape, InsideCornerShape, ImageShape, MeshShape>;

// Seeded noise on the shape's boundary, so each seed starts from a different
// rock of the same kind: the surface moves along its normal by amplitude ×
// fractal Perlin noise (at most `amplitude`, typically about a third of it).
struct ShapeVariation {
  double amplitude = 0.0;  // world units, >= 0; 0 = the shape as given
  double period = 1.0;     // world units, > 0
  int octaves = 1;         // 1..8
};

struct ShapeParams {
  ShapeKind kind = BoxShape{{2.0, 2.0, 2.0}};
  // Where the shape's centre (x, y) and base (z) go; default: centred in x, y,
  // resting on the ground.
  std::optional<Vec3d> center;
  std::optional<ShapeVariation> variation;  // none: the shape exactly
};

// ---- durability graph (docs/model.md §4) ----
struct NoiseParams {
  double amplitude = 0.0;  // durability units, >= 0
  double period = 1.0;     // world units, > 0
  int octaves = 1;         // 1..8
};
struct DurabilityGraph {
  // (altitude, durability), altitudes strictly increasing in [0, 1], durability > 0.
  std::vector<std::array<double, 2>> points{{0.0, 1.0}, {1.0, 1.0}};
  // One entry per segment (points.size() - 1 entries) or empty for none.
  std::vector<std::optional<NoiseParams>> noise;
};
// Geology beyond the paper's altitude graph (docs/model.md §4). Planes strike
// `strike` degrees clockwise from +y (seen from above) and dip `dip` degrees
// (0..90) towards the strike's right.
struct StrataParams {
  double dip = 0.0;             // degrees, 0..90; 0 = the paper's flat beds
  double strike = 0.0;          // degrees
  double warp_amplitude = 0.0;  // world units the beds are folded along their normal, >= 0
  double warp_period = 1.0;     // world units, > 0
};
struct JointSet {
  double strike = 0.0;   // degrees
  double dip = 90.0;     // degrees, 0..90
  double spacing = 1.0;  // world units between neighbouring planes, > 0
  double jitter = 0.0;   // world units: planes are spacing ± jitter apart, 0 <= jitter < spacing
  double width = 0.05;   // world units: durability changes within `width` of a plane, 0 < width < spacing
  double factor = 0.3;   // durability multiplier near a plane, > 0
};
struct RindParams {
  double depth = 0.1;   // world units below the initial surface, > 0
  double factor = 2.0;  // durability multiplier in the rind, > 0
};

// ---- bubbles (docs/model.md §3) ----
struct BubbleSpec {
  enum class Kind { Sphere, Ellipsoid, Box, Collection };
  Kind kind = Kind::Sphere;
  // Sphere: extents[0] = radius; Ellipsoid: radii; Box: half extents. World units.
  Vec3d extents{0.0, 0.0, 0.0};
  struct Member;
  std::vector<Member> members;  // Collection only
};
struct BubbleSpec::Member {
  BubbleSpec bubble;
  double weight = 1.0;  // > 0
};

struct BubbleBand {
  double up_to = 1.0;  // upper altitude of the band; bands strictly increasing, last = 1
  BubbleSpec bubble;
  double spheroidal = 1.0;  // k_s >= 0
  double cavernous = 0.0;   // k_c >= 0
};

// ---- decimation response f (docs/model.md §5) ----
struct ResponseParams {
  enum class Kind { Power, Threshold, Curve };
  Kind kind = Kind::Power;
  double value = 1.0;                        // power p > 0, or threshold t in [0, 1)
  std::vector<std::array<double, 2>> curve;  // Curve: x strictly increasing from 0 to 1
};

// ---- keyframes (docs/model.md §4) ----
// An edit during the simulation (docs/model.md §4, docs/studio.md): from time `at` on, each part
// it carries replaces the one in effect. At least one part is set.
struct DurabilityKeyframe {
  double at = 0.0;                                 // simulation time (world units of time), >= 0
  std::optional<DurabilityGraph> graph;            // points and noise; durability reassigned to standing rock
  std::optional<std::vector<BubbleBand>> bubbles;  // the bubble graph
  std::optional<ResponseParams> response;          // the decimation response
};
struct DurabilityParams {
  DurabilityGraph graph;
  std::vector<DurabilityKeyframe> keyframes;  // sorted by `at`
  // The rock's structure: it stays through keyframes (they replace the graph only).
  std::optional<StrataParams> strata;  // none: the graph is read by altitude
  std::vector<JointSet> joints;
  std::optional<RindParams> rind;
};

// ---- rockfall and colluvium (docs/model.md §6, §7) ----
enum class RockfallMode { Drop, Crumble, Off };
struct RockfallParams {
  RockfallMode mode = RockfallMode::Drop;
};
struct ColluviumParams {
  double yield = 0.5;         // units of colluvium per decimated rock voxel, 0..1
  double talus_angle = 35.0;  // degrees, 0 < angle < 90
  double removal = 0.0;       // fraction of exposed colluvium carried away per cycle, 0..1
};

// ---- how long to weather (docs/model.md §9) ----
struct StopParams {
  std::optional<double> time;                  // world units of time; cycles = ceil(time / h)
  std::optional<int> cycles;                   // exactly one of time / cycles is set
  std::optional<double> rock_volume_fraction;  // stop once rock <= fraction × initial
};

// ---- later stages (accepted and validated now; used by the mesh and render stages) ----
struct MeshParams {
  double smoothing = 1.0;  // 0..4
  int subdivision = 2;     // 0..3
  // LOD0 is the refined surface simplified until it would leave it by more than
  // this (voxels, > 0); 0.15 is invisible in the studio still at 1920 × 1080.
  double max_error = 0.15;
  // LOD1, LOD2, …: all ratios in (0, 1) of LOD0's triangles, or all triangle
  // counts (whole numbers >= 1, both surfaces together); decreasing.
  std::vector<double> lods;
  // Seeded roughness displaced along the refined surface's normals (world units);
  // none when absent.
  std::optional<NoiseParams> detail;
  // The debris apron's toe (docs/model.md §7, "The toe"): near its rim on the ground the colluvium
  // surface stays under a wedge rising from the rim at this angle, so the apron thins to nothing
  // instead of ending in a rounded lip. Degrees, 0..45; 0 keeps the voxels' rim.
  double apron_toe = 12.0;
  // How deep the asset is sunk into the ground (docs/meshes.md, "The pivot and the frames"): the
  // pivot, and so the ground plane, is raised by it. World units >= 0, or kSinkSuggested: by the
  // suggested burial depth (suggestedBurialDepth in mesh/extract_surfaces.h).
  static constexpr double kSinkSuggested = -1.0;
  double sink = 0.0;
};
enum class Palette { Natural, Debug, Curvature };
using SrgbColor = std::array<double, 3>;  // each channel in [0, 1]
struct PaletteLayer {
  double durability;  // the layer's durability, > 0
  SrgbColor color;
};
struct VertexPaletteParams {
  Palette palette = Palette::Natural;
  // `natural` palette: colours keyed by durability, interpolated between
  // layers (sorted by durability). Empty: built-in sandstone keyed to the
  // asset's durability range.
  std::vector<PaletteLayer> layers;
  std::optional<SrgbColor> colluvium_color;  // default a sandy buff
};
// ---- the look (docs/textures.md, "The look"; docs/model.md §14) ----
// Relief made by a surface process: `amplitude` (world units, >= 0; 0: off) at `spacing` (world
// units, > 0): the laminae's spacing, the exfoliation sheets' thickness, the pits' size.
struct LookRelief {
  double amplitude = 0.0;
  double spacing = 0.1;
};
// What the rock's weathering history makes of its surface, after the simulation. Strengths are
// 0 (off) … 4, 1 the house's; colours sRGB.
struct LookParams {
  static constexpr double kMaxStrength = 4.0;
  double stain = 1.0;     // streaks where water runs down the fall line and sheds at overhang lips
  double varnish = 1.0;   // long-exposed rock darkening towards desert varnish or patina
  double dust = 1.0;      // dust and soil on ledges and in upward-facing hollows
  double moisture = 1.0;  // a damp band at the foot and in sheltered overhangs
  double scars = 1.0;     // how much paler fresh rockfall scars and recently exposed faces are
  double lichen = 0.0;    // lichen on long-exposed, upward-facing rock
  SrgbColor stain_color{0x5C / 255.0, 0x45 / 255.0, 0x33 / 255.0};    // #5C4533
  SrgbColor varnish_color{0x33 / 255.0, 0x21 / 255.0, 0x1A / 255.0};  // #33211A
  SrgbColor dust_color{0xCD / 255.0, 0xB8 / 255.0, 0x9A / 255.0};     // #CDB89A
  SrgbColor lichen_color{0xA9 / 255.0, 0xAD / 255.0, 0x85 / 255.0};   // #A9AD85
  LookRelief laminations;  // ridges along the beds, the harder laminae standing out
  LookRelief exfoliation;  // sheets parallel to the surface on spheroidally weathered rock
  LookRelief pitting;      // granular pits on cavernously weathered rock
};
// ---- texture sets (docs/textures.md) ----
enum class TextureMap {
  BaseColor,  // <name>_BaseColor[_LOD<k>].png: 8-bit sRGB RGB
  Normal,     // <name>_Normal_LOD<k>.png: 16-bit RGB, tangent space, OpenGL convention (+Y up)
  Orm,        // <name>_ORM[_LOD<k>].png: 8-bit linear RGB, R occlusion, G roughness, B metal (0)
  Height,     // <name>_Height.exr (LOD0 only): 32-bit float, signed distance LOD0 → source, world units
  Mask,       // <name>_Mask[_LOD<k>].png: 8-bit linear RGBA, durability, colluvium, curvature, altitude
  History,    // <name>_History[_LOD<k>].png: 8-bit linear RGBA, exposure age, stain, moisture, dust (a look's)
};
// How big each LOD's maps are: `halved`, LOD k at size / 2^k (at least 256); `full`, every LOD at size.
enum class LodMapSize { Halved, Full };
// How the maps' files store what is baked (docs/textures.md §6).
enum class MapPrecision {
  Compact,  // 8-bit normal maps, half-float height: a game's or a library's set
  Full,     // 16-bit normal maps, 32-bit float height: as made, for film
};
struct TextureParams {
  int size = 2048;   // LOD0's map width and height, texels: a power of two, 256..8192
  int padding = 8;   // empty texels between charts, 0..64; every map is dilated into them
  int ao_rays = 32;  // ambient-occlusion rays per vertex, 1..1024
  // How far an occlusion ray looks, world units; 0: without limit (the whole asset occludes).
  double ao_distance = 0.0;
  // How far each texel's ray looks from the LOD's surface, both ways along its normal,
  // world units; 0: 5 % of the bake source's bounding-box diagonal.
  double cage = 0.0;
  // The History map is not listed: a bake with a look makes it, one without does not.
  std::vector<TextureMap> maps = {TextureMap::BaseColor, TextureMap::Normal, TextureMap::Orm, TextureMap::Height,
                                  TextureMap::Mask};
  LodMapSize lod_size = LodMapSize::Halved;
  MapPrecision precision = MapPrecision::Compact;
  // Texels a voxel the colour maps (base colour, ORM, mask, History: the voxels' fields and the
  // look, no finer than a voxel) keep at least: each LOD's are halved while they would keep this
  // many; the normal and height maps, whose relief is finer, keep the LOD's size. 0: every map
  // at the LOD's size. 0..64.
  double colour_density = 3.0;
};
struct RenderParams {
  std::string template_name = "studio";
  int width = 640;
  int height = 480;
  int quality = 9;                 // POV-Ray +Q: 0..11
  double antialias = 0.3;          // POV-Ray +A threshold; 0 turns antialiasing off
  int turntable_frames = 0;        // 0: no turntable
  int turntable_fps = 24;          // turntable.mp4's frame rate, 1 … 120
  bool turntable_lookdev = false;  // an 18 % grey ball, a colour chart and a three-point rig in frame
};

// Collision hulls decomposed from the voxels (docs/collision.md): the preset's
// `collision:` block, written to collision.glb when `export:` lists `collision`.
enum class HullNaming {
  Unreal,  // UCX_rock_lod0_00, UCX_rock_lod0_01, …: paired with rock.glb's mesh rock_lod0
  Godot,   // rock_lod0_00-convcolonly, …
};
struct CollisionParams {
  static constexpr int kMaxHulls = 100;     // two-digit node names
  static constexpr int kMinVertices = 8;    // the reduction starts from the bounding box
  static constexpr int kMaxVertices = 255;  // PhysX's (Unreal's, Unity's) limit per convex mesh
  int max_hulls = 16;                       // hulls per material, 1..kMaxHulls
  int max_vertices = 64;                    // vertices per hull, kMinVertices..kMaxVertices
  HullNaming naming = HullNaming::Unreal;   // node names in collision.glb
  bool colluvium = false;                   // also hull the colluvium, separately
};

// ---- delivery (docs/delivery.md) ----
// Where the files go: an engine's conventions and a compressed set beside the full one.
enum class DeliveryProfile {
  Generic,  // names as docs/formats.md gives them, maps as files beside the GLBs (OpenGL normals)
  Unreal,   // SM_/M_/T_ prefixes, UCX_ hulls, DirectX normal-map files, images embedded in the GLBs
  Godot,    // -convcolonly hulls, images embedded
  Unity,    // images embedded
};
struct DeliveryParams {
  DeliveryProfile profile = DeliveryProfile::Generic;
  // Also write compressed/: the GLBs with KTX2 (Basis Universal) maps and quantised,
  // meshopt-compressed meshes (docs/delivery.md). Needs the basisu and gltfpack programs.
  bool compressed = false;
};

// ---- clasts (docs/model.md §13) ----
// Stones on the debris apron (clasts/clasts.h): each a small weathered rock, placed after the
// simulation, exported as instances of a few shared meshes. Sizes are the stone's longest axis in
// voxels of the grid the bake runs at.
struct ClastParams {
  static constexpr int kMaxCount = 5000;
  static constexpr int kMinShapes = 6, kMaxShapes = 32;
  int count = 200;                        // stones placed at most, 1..kMaxCount
  std::array<double, 2> size{1.0, 10.0};  // smallest and largest stone, voxels, [0.5, 64], min <= max
  double size_exponent = 1.0;             // a: N(> s) ∝ s^-a between the two sizes, (0, 4]
  int shapes = 8;                         // distinct stone meshes, kMinShapes..kMaxShapes
};

// ---- families (docs/model.md §12) ----
// A preset's family: what a seed may change of the blockout, and by how much.
// Each seed draws one individual from these ranges (sim/family.h); the grid is
// then fitted to that individual. Intervals are [min, max] with min <= max.
using Interval = std::array<double, 2>;
struct FamilyWarp {
  double bend = 0.0;   // the top's sideways offset at most, as a fraction of the height, 0..1
  double taper = 0.0;  // the width's change from base to top at most, as a fraction, 0..0.9
  double twist = 0.0;  // the top's turn about the vertical at most, degrees, 0..180
};
struct FamilyFracture {
  std::array<int, 2> cuts{1, 2};  // how many cuts along the joint sets' planes, 0..8
  Interval depth{0.1, 0.35};      // how far each cut reaches into the shape, a fraction of its width, (0, 0.9]
};
enum class FamilyGeology { Turns, Fixed };
struct FamilyParams {
  Interval scale{1.0, 1.0};  // uniform size factor, > 0, drawn log-uniformly
  // Per-axis factors on top of scale, the blockout's own x, y and z (up), > 0, log-uniform.
  std::array<Interval, 3> stretch{{{1.0, 1.0}, {1.0, 1.0}, {1.0, 1.0}}};
  Interval azimuth{0.0, 360.0};  // turn about the vertical, degrees
  double tilt = 0.0;             // lean at most, degrees, 0..90, towards a seeded direction
  FamilyWarp warp;
  std::optional<FamilyFracture> fracture;  // none: the blockout is not cut
  // Turns: strata and joints turn with the blockout's azimuth (the rock is one
  // block of its bedrock); Fixed: the geology stays put in the world.
  FamilyGeology geology = FamilyGeology::Turns;
};

// What the simulation reads (docs/model.md): everything that decides the voxels.
struct SimParams {
  std::uint64_t seed = 0;  // every random choice derives from (seed, purpose, ...)
  GridParams grid;
  ShapeParams shape;
  std::optional<FamilyParams> family;  // none: every seed weathers the blockout as given
  DurabilityParams durability;
  std::vector<BubbleBand> bubbles;  // never empty after loading
  ResponseParams response;
  RockfallParams rockfall;
  ColluviumParams colluvium;
  StopParams stop;
};

// A validated preset: the simulation's parameters and those of the stages
// after it, each stage's in its own struct. Stages take the part they need
// (the simulation a SimParams, the mesh stage MeshParams and VertexPaletteParams, ...).
struct Preset : SimParams {
  std::filesystem::path file;  // where it was read from
  // Every file it was read from, absolute: the preset first, then the bases it
  // extends, nearest first (what a re-bake must watch for changes).
  std::vector<std::filesystem::path> sources;
  int schema = 1;    // `rockbake:` version
  std::string name;  // [a-z0-9_-]+
  MeshParams mesh;
  VertexPaletteParams bake;  // the `bake:` block: how the meshes' vertex colours are made
  CollisionParams collision;
  std::vector<std::string> exports{"ply", "glb", "vdb", "collision"};  // "obj" on request
  std::vector<std::string> tags;                                       // asset.json's tags, each [a-z0-9_-]+
  double units_per_meter = 1.0;  // world units per metre: the GLBs are written in metres, > 0
  DeliveryParams delivery;
  RenderParams render;
  // The texture set (UV atlases, tangent frames and baked maps on every LOD); none: the
  // meshes carry vertex colours only. The house style gives one.
  std::optional<TextureParams> texture;
  // Stones on the apron (docs/model.md §13); none: no stones. The house style gives them.
  std::optional<ClastParams> clasts;
  // The look made from the weathering history (docs/textures.md, "The look"); none (left out, or
  // `look: none`): the palette and its noise alone. The house style gives one.
  std::optional<LookParams> look;

  // Where each key the file gave was written, by key path ("shape.image.path"),
  // so that later stages place their errors too (an unreadable image, a shape
  // that covers no voxel).
  std::map<std::string, SourceLocation> locations;
  // The location of `key_path`, or of its nearest recorded parent, else the file.
  SourceLocation locate(const std::string& key_path) const;
};

}  // namespace rockbake
