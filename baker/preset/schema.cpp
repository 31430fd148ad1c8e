// The preset schema: one table of every key (docs/preset-reference.md).
//
// Each function below returns the MapSpec of one YAML map (preset/schema_spec.h):
// its keys in reading order, each with the member it fills, its value (type,
// range), whether it must be given, its checks (preset/schema_rules.h), unit,
// one-line doc and who may edit it. The reader, the JSON writer, `extends`
// merging, the studio's and `resume`'s edit lists and the reference page all
// walk these tables; nothing else lists keys.
//
// Adding a key: add its member to the struct in preset/preset.h (with its
// default), then one row to the map that holds it here, and regenerate the
// reference (`cmake --build build --target preset-reference`). For example
// render.turntable.fps is `int turntable_fps = 24;` in RenderParams and
//   k("fps", &RenderParams::turntable_fps, integer<int>(1, 120), "frames per second").unit("1/s"),
// in turntableSpec(). A new block (say `texture: {size, padding}`) is a struct
// in preset.h, a member of Preset, a `textureSpec()` here listing its keys, and
// one row in presetSpec():
//   k("texture", &Preset::texture, mapValue<textureSpec>(), "texture maps")
// A list of blocks uses listOfMaps<spec>(); a rule between keys is a named
// check in preset/schema_rules.h, given to the row with .check(). New enum
// values need a name in the enum's table below; a new kind of a one-of map
// (a shape, a bubble) is one row there, and `extends` merges it as one.
//
// Every key is in the resolved preset's JSON, and so in each asset's input
// hash: a new key with a default changes every preset's hash (a library re-run
// then bakes everything again). A std::optional member is written only when
// given (shape.variation, durability.strata), so presets without it keep
// their hash.
#include "preset/schema.h"

#include "preset/schema_rules.h"
#include "preset/schema_spec.h"
#include "preset/schema_values.h"

namespace rockbake::schema {

// ---- enum names ----

template <>
std::span<const EnumName<Palette>> enumNames() {
  static constexpr EnumName<Palette> names[] = {
      {Palette::Natural, "natural"}, {Palette::Debug, "debug"}, {Palette::Curvature, "curvature"}};
  return names;
}
template <>
std::span<const EnumName<RockfallMode>> enumNames() {
  static constexpr EnumName<RockfallMode> names[] = {
      {RockfallMode::Drop, "drop"}, {RockfallMode::Crumble, "crumble"}, {RockfallMode::Off, "off"}};
  return names;
}
template <>
std::span<const EnumName<ImageMode>> enumNames() {
  static constexpr EnumName<ImageMode> names[] = {{ImageMode::Extrude, "extrude"}, {ImageMode::Revolve, "revolve"}};
  return names;
}
template <>
std::span<const EnumName<BubbleSpec::Kind>> enumNames() {
  using K = BubbleSpec::Kind;
  static constexpr EnumName<K> names[] = {
      {K::Sphere, "sphere"}, {K::Ellipsoid, "ellipsoid"}, {K::Box, "box"}, {K::Collection, "collection"}};
  return names;
}
template <>
std::span<const EnumName<ResponseParams::Kind>> enumNames() {
  using K = ResponseParams::Kind;
  static constexpr EnumName<K> names[] = {{K::Power, "power"}, {K::Threshold, "threshold"}, {K::Curve, "curve"}};
  return names;
}

namespace {

constexpr const char* kWorld = "world units";
constexpr const char* kDegrees = "degrees";

// ---- shape (docs/model.md §8) ----

const MapSpec<BoxShape>& boxSpec() {
  static const Keys<BoxShape> k;
  static const MapSpec<BoxShape> spec{{
      k("size", &BoxShape::size, lengths3(), "the box's size along x, y, z").always().unit(kWorld),
  }};
  return spec;
}

const MapSpec<CylinderShape>& cylinderSpec() {
  static const Keys<CylinderShape> k;
  static const MapSpec<CylinderShape> spec{{
      k("radius", &CylinderShape::radius, length(), "radius of the upright cylinder").always().unit(kWorld),
      k("height", &CylinderShape::height, length(), "its height").always().unit(kWorld),
  }};
  return spec;
}

const MapSpec<SphereShape>& sphereSpec() {
  static const Keys<SphereShape> k;
  static const MapSpec<SphereShape> spec{{
      k("radius", &SphereShape::radius, length(), "the sphere's radius").always().unit(kWorld),
  }};
  return spec;
}

const MapSpec<InsideCornerShape>& insideCornerSpec() {
  static const Keys<InsideCornerShape> k;
  static const MapSpec<InsideCornerShape> spec{{
      k("size", &InsideCornerShape::size, lengths3(), "footprint x, y and height of the L-shaped block")
          .always()
          .unit(kWorld),
      k("wall", &InsideCornerShape::wall, length(),
        "thickness of its two walls, thinner than the footprint; the corner opens towards +x +y")
          .always()
          .unit(kWorld)
          .check(wallThinnerThanFootprint),
  }};
  return spec;
}

const MapSpec<ImageShape>& imageSpec() {
  static const Keys<ImageShape> k;
  static const MapSpec<ImageShape> spec{{
      k("path", &ImageShape::path, existingFile("image"), "a PNG: its bright pixels (>= 128) are rock").always(),
      k("mode", &ImageShape::mode, choice<ImageMode>(),
        "extrude: the image is the footprint; revolve: it is a profile turned about its left column"),
      k("height", &ImageShape::height, length(), "extrude: the extrusion's height; revolve: the profile's height")
          .always()
          .unit(kWorld),
  }};
  return spec;
}

const MapSpec<MeshShape>& meshShapeSpec() {
  static const Keys<MeshShape> k;
  static const MapSpec<MeshShape> spec{{
      k("path", &MeshShape::path, existingFile("mesh"), "a closed OBJ, PLY or STL blockout, voxelized").always(),
      k("scale", &MeshShape::scale, numberIn(0.0, kMaxWorldLength, true), "world units per file unit"),
  }};
  return spec;
}

const MapSpec<ShapeVariation>& variationSpec() {
  static const Keys<ShapeVariation> k;
  static const MapSpec<ShapeVariation> spec{{
      k("amplitude", &ShapeVariation::amplitude, numberIn(0.0, 1e6),
        "how far seeded fractal noise moves the boundary, at most (typically a third of it); 0 keeps the shape")
          .required("a variation needs 'amplitude' (world units; 0 keeps the shape)")
          .unit(kWorld),
      k("period", &ShapeVariation::period, positive(), "the noise's period").unit(kWorld),
      k("octaves", &ShapeVariation::octaves, integer<int>(1, 8), "octaves of the noise"),
  }};
  return spec;
}

const MapSpec<ShapeParams>& shapeSpec() {
  static const Keys<ShapeParams> k;
  static const MapSpec<ShapeParams> spec{
      {
          k.variant<BoxShape>("box", &ShapeParams::kind, mapValue<boxSpec>(), "a box"),
          k.variant<CylinderShape>("cylinder", &ShapeParams::kind, mapValue<cylinderSpec>(), "an upright cylinder"),
          k.variant<SphereShape>("sphere", &ShapeParams::kind, mapValue<sphereSpec>(), "a sphere"),
          k.variant<InsideCornerShape>("inside_corner", &ShapeParams::kind, mapValue<insideCornerSpec>(),
                                       "an L-shaped block: two walls meeting at a right angle"),
          k.variant<ImageShape>("image", &ShapeParams::kind, mapValue<imageSpec>(),
                                "a PNG footprint extruded, or a profile revolved"),
          k.variant<MeshShape>("mesh", &ShapeParams::kind, mapValue<meshShapeSpec>(), "an artist's blockout"),
          k("center", &ShapeParams::center, position(),
            "where the shape's centre (x, y) and base (z) go; default: centred in x, y, on the ground")
              .nullWhenAbsent()
              .unit(kWorld),
          k("variation", &ShapeParams::variation, mapValue<variationSpec>(),
            "seeded noise on the boundary: each seed starts from a different rock of the same kind"),
      },
      {kinds({"box", "cylinder", "sphere", "inside_corner", "image", "mesh"})},
      "Exactly one of `box`, `cylinder`, `sphere`, `inside_corner`, `image`, `mesh`: the shape's kind. "
      "Shapes are placed by their bounding box and fill the voxels whose centre is inside them."};
  return spec;
}

// ---- durability (docs/model.md §4) ----

const MapSpec<NoiseParams>& noiseSpec() {
  static const Keys<NoiseParams> k;
  static const MapSpec<NoiseParams> spec{{
      k("amplitude", &NoiseParams::amplitude, numberIn(0.0, 1e6), "the noise's amplitude"),
      k("period", &NoiseParams::period, length(), "its period").unit(kWorld),
      k("octaves", &NoiseParams::octaves, integer<int>(1, 8),
        "octaves, each at double the frequency and half the amplitude"),
  }};
  return spec;
}

const MapSpec<DurabilityGraph>& graphSpec() {
  static const Keys<DurabilityGraph> k;
  static const MapSpec<DurabilityGraph> spec{{
      k("points", &DurabilityGraph::points, altitudePoints(),
        "the durability graph: durability by altitude (0 ground .. 1 top of grid.size), constant beyond its ends")
          .keyframed(KeyframePart::Graph),
      k("noise", &DurabilityGraph::noise, listOfNullable(mapValue<noiseSpec>(), "list of noise maps or null"),
        "Perlin noise per segment of the graph: one entry per segment (null: none), or [] for none at all")
          .checkFirst(oneNoisePerSegment)
          .keyframed(KeyframePart::Graph)
          .inheritedWith("points"),
  }};
  return spec;
}

const MapSpec<StrataParams>& warpSpec() {
  static const Keys<StrataParams> k;
  static const MapSpec<StrataParams> spec{{
      k("amplitude", &StrataParams::warp_amplitude, numberIn(0.0, 1e6),
        "how far the beds are folded along their normal")
          .required("a warp needs 'amplitude' (world units)")
          .unit(kWorld),
      k("period", &StrataParams::warp_period, positive(), "the fold's period over the bedding plane")
          .required("a warp needs 'period' (world units)")
          .unit(kWorld),
  }};
  return spec;
}

const MapSpec<StrataParams>& strataSpec() {
  static const Keys<StrataParams> k;
  static const MapSpec<StrataParams> spec{{
      k("dip", &StrataParams::dip, numberIn(0.0, 90.0), "the beds' dip towards the strike's right; 0: flat beds")
          .unit(kDegrees),
      k("strike", &StrataParams::strike, numberIn(-360.0, 360.0), "clockwise from +y, seen from above").unit(kDegrees),
      k("warp", self, mapValue<warpSpec>(), "folds in the beds"),
  }};
  return spec;
}

const MapSpec<JointSet>& jointSpec() {
  static const Keys<JointSet> k;
  static const MapSpec<JointSet> spec{{
      k("strike", &JointSet::strike, numberIn(-360.0, 360.0), "the planes' strike, clockwise from +y").unit(kDegrees),
      k("dip", &JointSet::dip, numberIn(0.0, 90.0), "their dip").unit(kDegrees),
      k("spacing", &JointSet::spacing, positive(), "distance between neighbouring planes")
          .required("a joint set needs 'spacing' (world units between its planes)")
          .unit(kWorld),
      k("jitter", &JointSet::jitter, number(), "planes lie spacing ± jitter apart; 0 <= jitter < spacing")
          .unit(kWorld)
          .check(jitterBelowSpacing),
      k("width", &JointSet::width, positive(), "durability changes within this of a plane; less than spacing")
          .required("a joint set needs 'width' (world units either side of a plane)")
          .unit(kWorld)
          .check(widthBelowSpacing),
      k("factor", &JointSet::factor, positive(), "durability multiplier near a plane")
          .required("a joint set needs 'factor' (the durability multiplier at a plane, > 0)"),
  }};
  return spec;
}

const MapSpec<RindParams>& rindSpec() {
  static const Keys<RindParams> k;
  static const MapSpec<RindParams> spec{{
      k("depth", &RindParams::depth, positive(), "how deep below the initial surface the rind reaches")
          .required("a rind needs 'depth' (world units below the initial surface)")
          .unit(kWorld),
      k("factor", &RindParams::factor, positive(), "how many times as durable the rind is")
          .required("a rind needs 'factor' (how many times as durable, > 0)"),
  }};
  return spec;
}

const MapSpec<BubbleBand>& bandSpec();
const MapSpec<ResponseParams>& responseSpec();

Value<std::vector<BubbleBand>> bandList() {
  return listOfMaps<bandSpec>({"needs at least one band", true, lastBandReachesTheTop},
                              "list of bands, bottom to top, the last with up_to: 1");
}

const MapSpec<DurabilityKeyframe>& keyframeSpec() {
  static const Keys<DurabilityKeyframe> k;
  static const MapSpec<DurabilityKeyframe> spec{{
      k.inlined<graphSpec>(&DurabilityKeyframe::graph, "points"),
      k("at", &DurabilityKeyframe::at, numberIn(0.0, 1e9),
        "the simulation time from which its parts replace those in effect; keyframes in time order")
          .requiredHere("a keyframe needs 'at' (the simulation time it takes effect)")
          .checkFirst(keyframeChangesSomething)
          .checkFirst(noiseNeedsPoints)
          .check(keyframesInTimeOrder)
          .unit("units of time"),
      k("bubbles", &DurabilityKeyframe::bubbles, bandList(), "a bubble graph that replaces the one in effect"),
      k("response", &DurabilityKeyframe::response, mapValue<responseSpec>(),
        "a response that replaces the one in effect"),
  }};
  return spec;
}

const MapSpec<DurabilityParams>& durabilitySpec() {
  static const Keys<DurabilityParams> k;
  static const MapSpec<DurabilityParams> spec{{
      k.inlined<graphSpec>(&DurabilityParams::graph),
      k("strata", &DurabilityParams::strata, mapValue<strataSpec>(),
        "tilted and folded beds: the graph is read across them"),
      k("joints", &DurabilityParams::joints, listOfMaps<jointSpec>(), "sets of fracture planes").leftOutWhenEmpty(),
      k("rind", &DurabilityParams::rind, mapValue<rindSpec>(), "a case-hardened skin"),
      k("keyframes", &DurabilityParams::keyframes, listOfMaps<keyframeSpec>(),
        "edits during the run: each carries a graph (points and its own noise), bubbles or a response"),
  }};
  return spec;
}

// ---- bubbles and response (docs/model.md §3, §5) ----

const MapSpec<BubbleSpec>& bubbleSphereSpec() {
  static const Keys<BubbleSpec> k;
  static const MapSpec<BubbleSpec> spec{{
      k(
          "radius", [](auto& b) -> auto& { return b.extents[0]; }, length(), "the sphere's radius")
          .always()
          .unit(kWorld),
  }};
  return spec;
}

const MapSpec<BubbleSpec>& bubbleEllipsoidSpec() {
  static const Keys<BubbleSpec> k;
  static const MapSpec<BubbleSpec> spec{{
      k("radii", &BubbleSpec::extents, lengths3(), "the ellipsoid's radii along x, y, z").always().unit(kWorld),
  }};
  return spec;
}

const MapSpec<BubbleSpec>& bubbleBoxSpec() {
  static const Keys<BubbleSpec> k;
  static const MapSpec<BubbleSpec> spec{{
      k("half_extents", &BubbleSpec::extents, lengths3(), "the box's half extents along x, y, z").always().unit(kWorld),
  }};
  return spec;
}

const MapSpec<BubbleSpec>& bubbleSpec();

const MapSpec<BubbleSpec::Member>& memberSpec() {
  static const Keys<BubbleSpec::Member> k;
  static const MapSpec<BubbleSpec::Member> spec{{
      k("bubble", &BubbleSpec::Member::bubble, mapValue<bubbleSpec>(), "the member's bubble")
          .requiredHere("a collection member needs a bubble"),
      k("weight", &BubbleSpec::Member::weight, positive(), "its share of the bubbles placed"),
  }};
  return spec;
}

const MapSpec<BubbleSpec>& bubbleSpec() {
  using Kind = BubbleSpec::Kind;
  static const Keys<BubbleSpec> k;
  static const MapSpec<BubbleSpec> spec{
      {
          k.kind(Kind::Sphere, self, mapValue<bubbleSphereSpec>(), "a sphere"),
          k.kind(Kind::Ellipsoid, self, mapValue<bubbleEllipsoidSpec>(), "an ellipsoid, axis-aligned"),
          k.kind(Kind::Box, self, mapValue<bubbleBoxSpec>(), "a box, axis-aligned"),
          k.kind(Kind::Collection, &BubbleSpec::members,
                 listOfMaps<memberSpec>({"a collection needs at least one member"}),
                 "several bubbles, each placed in proportion to its weight"),
      },
      {kinds(namesOf<Kind>())},
      "Exactly one of `sphere`, `ellipsoid`, `box`, `collection`: the bubble's kind. Every extent spans at least "
      "one voxel and at most " +
          formatNumber(kMaxBubbleVoxels) + " at the preset's resolution."};
  return spec;
}

const MapSpec<BubbleBand>& bandSpec() {
  static const Keys<BubbleBand> k;
  static const MapSpec<BubbleBand> spec{{
      k("up_to", &BubbleBand::up_to, numberIn(0.0, 1.0, true), "the band's top altitude; bands go bottom to top")
          .requiredHere("a band needs 'up_to' (its top altitude, 0..1)")
          .check(bandsGoUp),
      k("bubble", &BubbleBand::bubble, mapValue<bubbleSpec>(), "the bubble that measures curvature in the band")
          .requiredHere("a band needs a 'bubble'")
          .check(bubbleFitsTheGrid),
      k("spheroidal", &BubbleBand::spheroidal, numberIn(0.0, 1e6), "k_s: how strongly convex rock rounds"),
      k("cavernous", &BubbleBand::cavernous, numberIn(0.0, 1e6), "k_c: how strongly concave rock hollows"),
  }};
  return spec;
}

const MapSpec<ResponseParams>& responseSpec() {
  using Kind = ResponseParams::Kind;
  static const Keys<ResponseParams> k;
  static const MapSpec<ResponseParams> spec{
      {
          k.kind(Kind::Power, &ResponseParams::value, positive(), "f(s) = s^p"),
          k.kind(Kind::Threshold, &ResponseParams::value, numberIn(0.0, 1.0, false, true),
                 "f(s) = 1 where s > t, else 0"),
          k.kind(Kind::Curve, &ResponseParams::curve, responseCurve(), "f read off a polyline"),
      },
      {kinds(namesOf<Kind>())},
      "Exactly one of `power`, `threshold`, `curve`: the decimation response f of the exposure s."};
  return spec;
}

// ---- simulation, mesh, bake, render ----

const MapSpec<GridParams>& gridSpec() {
  static const Keys<GridParams> k;
  static const MapSpec<GridParams> spec{{
      k("size", &GridParams::size, lengths3(), "the simulation domain along x, y, z").unit(kWorld),
      k("resolution", &GridParams::resolution, integer<int>(GridParams::kMinResolution, GridParams::kMaxResolution),
        "voxels along the longest side; the voxel size h is that side / resolution"),
      k("ground", &GridParams::ground, boolean(), "false: a free-floating rock, rockfall and colluvium off"),
  }};
  return spec;
}

const MapSpec<RockfallParams>& rockfallSpec() {
  static const Keys<RockfallParams> k;
  static const MapSpec<RockfallParams> spec{{
      k("mode", &RockfallParams::mode, choice<RockfallMode>(),
        "what unsupported rock does: falls whole, falls and crumbles to colluvium, or stays"),
  }};
  return spec;
}

const MapSpec<ColluviumParams>& colluviumSpec() {
  static const Keys<ColluviumParams> k;
  static const MapSpec<ColluviumParams> spec{{
      k("yield", &ColluviumParams::yield, numberIn(0.0, 1.0), "units of colluvium per decimated rock voxel"),
      k("talus_angle", &ColluviumParams::talus_angle, numberIn(0.0, 90.0, true, true), "the angle debris rests at")
          .unit(kDegrees),
      k("removal", &ColluviumParams::removal, numberIn(0.0, 1.0),
        "the fraction of exposed colluvium carried away per cycle"),
  }};
  return spec;
}

const MapSpec<StopParams>& untilSpec() {
  static const Keys<StopParams> k;
  static const MapSpec<StopParams> spec{{
      k("rock_volume_fraction", &StopParams::rock_volume_fraction, numberIn(0.0, 1.0, true, true),
        "stop after the first cycle that leaves at most this fraction of the initial rock"),
  }};
  return spec;
}

const MapSpec<MeshParams>& meshSpec() {
  static const Keys<MeshParams> k;
  static const MapSpec<MeshParams> spec{{
      k("smoothing", &MeshParams::smoothing, numberIn(0.0, 4.0), "Gaussian passes over the voxel level set"),
      k("subdivision", &MeshParams::subdivision, integer<int>(0, 3), "levels of Catmull-Clark subdivision"),
      k("max_error", &MeshParams::max_error, numberIn(0.0, 8.0, true),
        "LOD0 is simplified until it would leave the refined surface by more than this")
          .unit("voxels"),
      k("lods", &MeshParams::lods, lodList(), "LOD1, LOD2, ...: ratios of LOD0's triangles or triangle counts"),
      k("detail", &MeshParams::detail, mapValue<noiseSpec>(),
        "seeded roughness along the refined surface's normals (RMS about amplitude); none when absent"),
  }};
  return spec;
}

const MapSpec<PaletteLayer>& layerSpec() {
  static const Keys<PaletteLayer> k;
  static const MapSpec<PaletteLayer> spec{{
      k("durability", &PaletteLayer::durability, positive(), "the layer's durability; layers from soft to durable")
          .requiredHere("a layer needs durability and color")
          .check(layersSoftToDurable),
      k("color", &PaletteLayer::color, color(), "its colour").requiredHere("a layer needs durability and color"),
  }};
  return spec;
}

const MapSpec<BakeParams>& bakeSpec() {
  static const Keys<BakeParams> k;
  static const MapSpec<BakeParams> spec{{
      k("palette", &BakeParams::palette, choice<Palette>(),
        "natural: the layers' colours; debug: blue soft .. red durable; curvature: blue concave .. red convex"),
      k("layers", &BakeParams::layers, listOfMaps<layerSpec>(),
        "natural colours keyed by durability, interpolated; none: a built-in sandstone"),
      k("colluvium_color", &BakeParams::colluvium_color, color(), "the colluvium's colour; default a sandy buff"),
  }};
  return spec;
}

const MapSpec<RenderParams>& turntableSpec() {
  static const Keys<RenderParams> k;
  static const MapSpec<RenderParams> spec{{
      k("frames", &RenderParams::turntable_frames, integer<int>(0, 360), "views around z; 0: no turntable"),
  }};
  return spec;
}

const MapSpec<RenderParams>& renderSpec() {
  static const Keys<RenderParams> k;
  static const MapSpec<RenderParams> spec{{
      k("template", &RenderParams::template_name, templateName(), "the POV-Ray template, by name"),
      k("width", &RenderParams::width, integer<int>(16, 8192), "image width").unit("pixels"),
      k("height", &RenderParams::height, integer<int>(16, 8192), "image height").unit("pixels"),
      k("quality", &RenderParams::quality, integer<int>(0, 11), "POV-Ray +Q"),
      k("antialias", &RenderParams::antialias, numberIn(0.0, 3.0), "POV-Ray +A threshold; 0 turns it off"),
      k("turntable", self, mapValue<turntableSpec>(), "views around the rock and their contact sheet"),
  }};
  return spec;
}

// ---- the preset ----

constexpr auto stopTime = [](auto& p) -> auto& {
  return p.stop.time;
};
constexpr auto stopCycles = [](auto& p) -> auto& {
  return p.stop.cycles;
};

const MapSpec<Preset>& presetSpec() {
  static const Keys<Preset> k;
  static const MapSpec<Preset> spec{
      {
          k("rockbake", &Preset::schema, schemaVersion(), "the schema version")
              .required("missing 'rockbake: 1' (the schema version)"),
          k.refused("extends", "path of a base preset, relative to this file", refuseExtendsOverride,
                    "a base preset merged under this one (above)"),
          k("name", &Preset::name, assetName(), "the asset's name: it names the output folder")
              .required("missing 'name' (the asset's name, [a-z0-9_-]+)"),
          k("seed", &Preset::seed, unsigned64(), "every random choice derives from it"),
          k("grid", &Preset::grid, mapValue<gridSpec>(), "the simulation domain"),
          k("shape", &Preset::shape, mapValue<shapeSpec>(), "the initial rock")
              .required("missing 'shape'", "for example shape: {box: {size: [2, 2, 2]}}"),
          k("durability", &Preset::durability, mapValue<durabilitySpec>(), "how durable the rock is, and where"),
          k("bubbles", &Preset::bubbles, bandList(), "the bubble graph: bubbles and weathering strengths by altitude")
              .keyframed(KeyframePart::Bubbles)
              .byDefault(defaultBubbles, "one band: a sphere of radius 1/16 of grid.size's longest side, within 1 .. " +
                                             formatNumber(kMaxBubbleVoxels) + " voxels; spheroidal 1"),
          k("response", &Preset::response, mapValue<responseSpec>(), "the decimation response")
              .keyframed(KeyframePart::Response),
          k("rockfall", &Preset::rockfall, mapValue<rockfallSpec>(), "loose rock").resumable(),
          k("colluvium", &Preset::colluvium, mapValue<colluviumSpec>(), "debris").resumable(),
          k("time", stopTime, positive(), "how long to weather: ceil(time / h) cycles, the same rock at any resolution")
              .check(timeWithinCycleLimit)
              .resumable()
              .unit("units of time"),
          k("cycles", stopCycles, integer<int>(1, kMaxCycles), "how many cycles to run (resolution dependent)")
              .resumable(),
          k("until", &Preset::stop, mapValue<untilSpec>(), "stop early").leftOutWhenEmpty().resumable(),
          k("mesh", &Preset::mesh, mapValue<meshSpec>(), "meshes and LODs"),
          k("bake", &Preset::bake, mapValue<bakeSpec>(), "colours baked into the meshes"),
          k("export", &Preset::exports, exportFormats(), "the files a bake writes"),
          k("tags", &Preset::tags, tagList(), "asset.json's tags"),
          k("units_per_meter", &Preset::units_per_meter, numberIn(0.0, 1e6, true),
            "world units per metre: asset.json's physical size"),
          k("render", &Preset::render, mapValue<renderSpec>(), "the still render"),
      },
      {exactlyOne({"time", "cycles"}, "missing 'time' (or 'cycles')", "give either 'time' or 'cycles', not both",
                  "time: T runs ceil(T / voxel size) cycles, the same rock at any resolution")},
      "Exactly one of `time` and `cycles`.",
      /*keys_apart=*/true};
  return spec;
}

// ---- walking the table ----

std::string join(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

// Calls visit(path, key) for every key reached through maps from `map` (lists are not entered; keys
// written inline count as their map's own).
template <class Visit>
void forEachKeyThroughMaps(const MapInfo& map, const std::string& path, Visit&& visit) {
  for (const KeyInfo& key : map.keys) {
    if (key.name.empty()) {
      forEachKeyThroughMaps(key.map(), path, visit);
      continue;
    }
    visit(path, key);
    if (key.map && !key.list) forEachKeyThroughMaps(key.map(), join(path, key.name), visit);
  }
}

// Calls visit(path, map) for every map reached through maps, inline ones at their map's path.
template <class Visit>
void forEachMapThroughMaps(const MapInfo& map, const std::string& path, Visit&& visit) {
  visit(path, map);
  for (const KeyInfo& key : map.keys) {
    if (key.name.empty())
      forEachMapThroughMaps(key.map(), path, visit);
    else if (key.map && !key.list)
      forEachMapThroughMaps(key.map(), join(path, key.name), visit);
  }
}

}  // namespace

const MapSpec<Preset>& presetTable() {
  return presetSpec();
}

std::vector<std::string> keyframedKeys() {
  std::vector<std::string> keys;
  forEachKeyThroughMaps(presetSpec().info, "", [&](const std::string& path, const KeyInfo& key) {
    if (key.keyframe) keys.push_back(join(path, key.name));
  });
  return keys;
}

std::vector<std::string> resumableKeys() {
  std::vector<std::string> keys;
  forEachKeyThroughMaps(presetSpec().info, "", [&](const std::string& path, const KeyInfo& key) {
    if (key.resume) keys.push_back(join(path, key.name));
  });
  return keys;
}

std::optional<KeyframePart> keyframePartOf(const std::string& key_path) {
  std::optional<KeyframePart> part;
  forEachKeyThroughMaps(presetSpec().info, "", [&](const std::string& path, const KeyInfo& key) {
    if (key.keyframe && underKeyPath(key_path, join(path, key.name))) part = key.keyframe;
  });
  return part;
}

const std::vector<MergeRule>& mergeRules() {
  static const std::vector<MergeRule> rules = [] {
    std::vector<MergeRule> out;
    forEachMapThroughMaps(presetSpec().info, "", [&](const std::string& path, const MapInfo& map) {
      for (const auto& group : map.alternatives) out.push_back({path, group.names, group.names});
      for (const auto& key : map.keys)
        if (!key.inherited_with.empty()) out.push_back({path, {key.inherited_with}, {key.name}});
    });
    return out;
  }();
  return rules;
}

std::vector<std::string> siblingsReplacedBy(const std::string& key_path) {
  std::vector<std::string> siblings;
  forEachMapThroughMaps(presetSpec().info, "", [&](const std::string& path, const MapInfo& map) {
    for (const auto& group : map.alternatives)
      if (!group.kind)
        for (const auto& name : group.names)
          if (join(path, name) == key_path)
            for (const auto& other : group.names)
              if (other != name) siblings.push_back(other);
  });
  return siblings;
}

}  // namespace rockbake::schema
