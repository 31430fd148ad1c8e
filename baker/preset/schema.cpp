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
std::span<const EnumName<HullNaming>> enumNames() {
  static constexpr EnumName<HullNaming> names[] = {{HullNaming::Unreal, "unreal"}, {HullNaming::Godot, "godot"}};
  return names;
}
template <>
std::span<const EnumName<DeliveryProfile>> enumNames() {
  static constexpr EnumName<DeliveryProfile> names[] = {{DeliveryProfile::Generic, "generic"},
                                                        {DeliveryProfile::Unreal, "unreal"},
                                                        {DeliveryProfile::Godot, "godot"},
                                                        {DeliveryProfile::Unity, "unity"}};
  return names;
}
template <>
std::span<const EnumName<MapPrecision>> enumNames() {
  static constexpr EnumName<MapPrecision> names[] = {{MapPrecision::Compact, "compact"}, {MapPrecision::Full, "full"}};
  return names;
}
template <>
std::span<const EnumName<ResponseParams::Kind>> enumNames() {
  using K = ResponseParams::Kind;
  static constexpr EnumName<K> names[] = {{K::Power, "power"}, {K::Threshold, "threshold"}, {K::Curve, "curve"}};
  return names;
}

template <>
std::span<const EnumName<TextureMap>> enumNames() {
  static constexpr EnumName<TextureMap> names[] = {{TextureMap::BaseColor, "base_color"},
                                                   {TextureMap::Normal, "normal"},
                                                   {TextureMap::Orm, "orm"},
                                                   {TextureMap::Height, "height"},
                                                   {TextureMap::Mask, "mask"}};
  return names;
}
template <>
std::span<const EnumName<LodMapSize>> enumNames() {
  static constexpr EnumName<LodMapSize> names[] = {{LodMapSize::Halved, "halved"}, {LodMapSize::Full, "full"}};
  return names;
}

template <>
std::span<const EnumName<UpAxis>> enumNames() {
  static constexpr EnumName<UpAxis> names[] = {{UpAxis::Z, "z"}, {UpAxis::Y, "y"}};
  return names;
}
template <>
std::span<const EnumName<FamilyGeology>> enumNames() {
  static constexpr EnumName<FamilyGeology> names[] = {{FamilyGeology::Turns, "turns"}, {FamilyGeology::Fixed, "fixed"}};
  return names;
}

namespace {

constexpr const char* kWorld = "world units";
constexpr const char* kDegrees = "degrees";

// ---- shape (docs/model.md §8) ----

const MapSpec<BoxShape>& boxSpec() {
  static const Keys<BoxShape> k;
  static const MapSpec<BoxShape> spec{{
      k("size", &BoxShape::size, lengths3(), "an axis-aligned box").always().unit(kWorld),
  }};
  return spec;
}

const MapSpec<CylinderShape>& cylinderSpec() {
  static const Keys<CylinderShape> k;
  static const MapSpec<CylinderShape> spec{{
      k("radius", &CylinderShape::radius, length(), "a vertical cylinder's radius").always().unit(kWorld),
      k("height", &CylinderShape::height, length(), "its height").always().unit(kWorld),
  }};
  return spec;
}

const MapSpec<SphereShape>& sphereSpec() {
  static const Keys<SphereShape> k;
  static const MapSpec<SphereShape> spec{{
      k("radius", &SphereShape::radius, length(), "a sphere resting on the base").always().unit(kWorld),
  }};
  return spec;
}

const MapSpec<InsideCornerShape>& insideCornerSpec() {
  static const Keys<InsideCornerShape> k;
  static const MapSpec<InsideCornerShape> spec{{
      k("size", &InsideCornerShape::size, lengths3(), "an L-shaped block's footprint x, y and height")
          .always()
          .unit(kWorld),
      k("wall", &InsideCornerShape::wall, length(),
        "the thickness of its two walls; the re-entrant corner opens towards +x +y")
          .always()
          .unit(kWorld)
          .range("< `min(size[0], size[1])`")
          .check(wallThinnerThanFootprint),
  }};
  return spec;
}

const MapSpec<ImageShape>& imageSpec() {
  static const Keys<ImageShape> k;
  static const MapSpec<ImageShape> spec{{
      k("path", &ImageShape::path, existingFile("image", "a PNG"), "a black-and-white image: white (≥ 128) is rock")
          .always(),
      k("mode", &ImageShape::mode, choice<ImageMode>(),
        "the image as a footprint, or as a profile revolved about z (left column = axis)"),
      k("height", &ImageShape::height, length(), "extrusion height, or the height the profile's rows span")
          .always()
          .unit(kWorld),
  }};
  return spec;
}

const MapSpec<MeshShape>& meshShapeSpec() {
  static const Keys<MeshShape> k;
  static const MapSpec<MeshShape> spec{{
      k("path", &MeshShape::path, existingFile("mesh", "a closed OBJ, PLY or STL, ≤ 1 GiB"),
        "an artist's blockout, voxelised")
          .always(),
      k("scale", &MeshShape::scale, numberIn(0.0, kMaxWorldLength, true), "scales the blockout's coordinates")
          .unit("world units per file unit"),
      k("up", &MeshShape::up, choice<UpAxis>(),
        "the file's up axis: `y` for OBJ or glTF written y-up (a file's (x, y, z) is then the world's (x, −z, y))"),
  }};
  return spec;
}

const MapSpec<ShapeVariation>& variationSpec() {
  static const Keys<ShapeVariation> k;
  static const MapSpec<ShapeVariation> spec{{
      k("amplitude", &ShapeVariation::amplitude, numberIn(0.0, 1e6),
        "how far seeded noise may move the boundary; 0 keeps the shape")
          .required("a variation needs 'amplitude' (world units; 0 keeps the shape)")
          .unit(kWorld),
      k("period", &ShapeVariation::period, positive(), "the noise's feature size").unit(kWorld),
      k("octaves", &ShapeVariation::octaves, integer<int>(1, 8), "octaves of fractal noise"),
  }};
  return spec;
}

const MapSpec<ShapeParams>& shapeSpec() {
  static const Keys<ShapeParams> k;
  static const MapSpec<ShapeParams> spec{
      {
          k.variant<BoxShape>("box", &ShapeParams::kind, mapValue<boxSpec>(), "a box"),
          k.variant<CylinderShape>("cylinder", &ShapeParams::kind, mapValue<cylinderSpec>(), "a cylinder"),
          k.variant<SphereShape>("sphere", &ShapeParams::kind, mapValue<sphereSpec>(), "a sphere"),
          k.variant<InsideCornerShape>("inside_corner", &ShapeParams::kind, mapValue<insideCornerSpec>(),
                                       "an L-shaped block"),
          k.variant<ImageShape>("image", &ShapeParams::kind, mapValue<imageSpec>(), "an image"),
          k.variant<MeshShape>("mesh", &ShapeParams::kind, mapValue<meshShapeSpec>(), "a blockout"),
          k("center", &ShapeParams::center, position(), "where the shape's centre (x, y) and base (z) go")
              .nullWhenAbsent()
              .unit(kWorld)
              .defaultIs("centred in x, y, on the ground"),
          k("variation", &ShapeParams::variation, mapValue<variationSpec>(), "seeded noise on the boundary"),
      },
      {kinds({"box", "cylinder", "sphere", "inside_corner", "image", "mesh"})},
      "Exactly one kind, and beside it optionally `center` and `variation` ([model.md §8](model.md)). Images "
      "are at most 256 M pixels, in any PNG format (alpha composited over black). A blockout must be closed: "
      "every edge shared by exactly two faces of opposite orientation."};
  return spec;
}

// ---- families (docs/model.md §12) ----

const MapSpec<FamilyWarp>& familyWarpSpec() {
  static const Keys<FamilyWarp> k;
  static const MapSpec<FamilyWarp> spec{{
      k("bend", &FamilyWarp::bend, numberIn(0.0, 1.0), "the top's sideways offset at most, a fraction of the height"),
      k("taper", &FamilyWarp::taper, numberIn(0.0, 0.9), "the width's change from base to top at most, a fraction"),
      k("twist", &FamilyWarp::twist, numberIn(0.0, 180.0), "the top's turn about the vertical at most").unit(kDegrees),
  }};
  return spec;
}

const MapSpec<FamilyFracture>& familyFractureSpec() {
  static const Keys<FamilyFracture> k;
  static const MapSpec<FamilyFracture> spec{{
      k("cuts", &FamilyFracture::cuts, wholeInterval(0, 8), "how many cuts along the joint sets' planes"),
      k("depth", &FamilyFracture::depth, interval(0.0, 0.9, true),
        "how far each cut reaches into the shape, a fraction of its width across the plane"),
  }};
  return spec;
}

const MapSpec<FamilyParams>& familySpec() {
  static const Keys<FamilyParams> k;
  static const MapSpec<FamilyParams> spec{
      {
          k("scale", &FamilyParams::scale, interval(0.0, 100.0, true), "the individual's size factor (log-uniform)"),
          k("stretch", &FamilyParams::stretch, axisIntervals(0.0, 100.0),
            "factors along the blockout's own x, y and z on top of scale: its proportions (log-uniform)"),
          k("azimuth", &FamilyParams::azimuth, interval(-360.0, 360.0), "its turn about the vertical").unit(kDegrees),
          k("tilt", &FamilyParams::tilt, numberIn(0.0, 90.0), "its lean at most, towards a seeded direction")
              .unit(kDegrees),
          k("warp", &FamilyParams::warp, mapValue<familyWarpSpec>(), "a low-frequency bend, taper and twist"),
          k("fracture", &FamilyParams::fracture, mapValue<familyFractureSpec>(),
            "cuts along the preset's joint sets: a joint-bounded block"),
          k("geology", &FamilyParams::geology, choice<FamilyGeology>(),
            "whether strata and joints turn with the azimuth (`turns`) or stay put (`fixed`)"),
      },
      {},
      "What a seed may change of the blockout; each seed draws one individual, and the grid is fitted to it "
      "([model.md §12](model.md)). Ranges are `[min, max]`; a range with min = max fixes the value."};
  return spec;
}

// ---- durability (docs/model.md §4) ----

const MapSpec<NoiseParams>& noiseSpec() {
  static const Keys<NoiseParams> k;
  static const MapSpec<NoiseParams> spec{{
      k("amplitude", &NoiseParams::amplitude, numberIn(0.0, 1e6), "noise amplitude added to the graph")
          .unit("durability"),
      k("period", &NoiseParams::period, length(), "the noise's feature size").unit(kWorld),
      k("octaves", &NoiseParams::octaves, integer<int>(1, 8), "octaves"),
  }};
  return spec;
}

const MapSpec<DurabilityGraph>& graphSpec() {
  static const Keys<DurabilityGraph> k;
  static const MapSpec<DurabilityGraph> spec{{
      k("points", &DurabilityGraph::points, altitudePoints(),
        "the durability graph: linear between points, constant beyond the ends")
          .unit("altitude, durability")
          .keyframed(KeyframePart::Graph),
      k("noise", &DurabilityGraph::noise, listOfNullable(mapValue<noiseSpec>()),
        "Perlin noise per segment; `null` for a segment without")
          .range("one entry per segment (`points` − 1), or `[]`")
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
        "how far seeded noise folds the beds along their normal")
          .required("a warp needs 'amplitude' (world units)")
          .unit(kWorld),
      k("period", &StrataParams::warp_period, positive(), "the folds' size along the beds")
          .required("a warp needs 'period' (world units)")
          .unit(kWorld),
  }};
  return spec;
}

const MapSpec<StrataParams>& strataSpec() {
  static const Keys<StrataParams> k;
  static const MapSpec<StrataParams> spec{{
      k("dip", &StrataParams::dip, numberIn(0.0, 90.0), "how steeply the beds dip; 0 is the paper's flat beds")
          .unit(kDegrees),
      k("strike", &StrataParams::strike, numberIn(-360.0, 360.0), "the beds' strike; they dip towards its right")
          .unit("degrees clockwise from +y"),
      k("warp", self, mapValue<warpSpec>(), "folds in the beds"),
  }};
  return spec;
}

const MapSpec<JointSet>& jointSpec() {
  static const Keys<JointSet> k;
  static const MapSpec<JointSet> spec{{
      k("strike", &JointSet::strike, numberIn(-360.0, 360.0), "the set's strike").unit(kDegrees),
      k("dip", &JointSet::dip, numberIn(0.0, 90.0), "the set's dip").unit(kDegrees),
      k("spacing", &JointSet::spacing, positive(), "distance between neighbouring planes")
          .required("a joint set needs 'spacing' (world units between its planes)")
          .unit(kWorld),
      k("jitter", &JointSet::jitter, number(), "planes are `spacing ± jitter` apart, placed by the seed")
          .unit(kWorld)
          .range("[0, `spacing`)")
          .check(jitterBelowSpacing),
      k("width", &JointSet::width, positive(), "durability changes within `width` of a plane")
          .required("a joint set needs 'width' (world units either side of a plane)")
          .unit(kWorld)
          .range("> 0 and < `spacing`")
          .check(widthBelowSpacing),
      k("factor", &JointSet::factor, positive(), "durability multiplier near a plane (below 1 weakens)")
          .required("a joint set needs 'factor' (the durability multiplier at a plane, > 0)"),
  }};
  return spec;
}

const MapSpec<RindParams>& rindSpec() {
  static const Keys<RindParams> k;
  static const MapSpec<RindParams> spec{{
      k("depth", &RindParams::depth, positive(), "depth below the initial surface that is hardened")
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
  return listOfMaps<bandSpec>({"needs at least one band", true, lastBandReachesTheTop});
}

const MapSpec<DurabilityKeyframe>& keyframeSpec() {
  static const Keys<DurabilityKeyframe> k;
  static const MapSpec<DurabilityKeyframe> spec{
      {
          k.inlined<graphSpec>(&DurabilityKeyframe::graph, "points").see("durability"),
          k("at", &DurabilityKeyframe::at, numberIn(0.0, 1e9), "the simulation time it takes effect")
              .requiredHere("a keyframe needs 'at' (the simulation time it takes effect)")
              .checkFirst(keyframeChangesSomething)
              .checkFirst(noiseNeedsPoints)
              .check(keyframesInTimeOrder)
              .unit("time"),
          k("bubbles", &DurabilityKeyframe::bubbles, bandList(), "the bubble graph it switches to").see("bubbles"),
          k("response", &DurabilityKeyframe::response, mapValue<responseSpec>(), "the response it switches to")
              .see("response"),
      },
      {},
      "**Keyframes** (`durability.keyframes.[]`), each a map, in time order (equal times allowed), carry at least "
      "one of `points` (with its own `noise`, none if absent: `noise` needs `points`), `bubbles` and `response`, "
      "each of which replaces the one in effect from `at` on ([model.md §4](model.md))."};
  return spec;
}

const MapSpec<DurabilityParams>& durabilitySpec() {
  static const Keys<DurabilityParams> k;
  static const MapSpec<DurabilityParams> spec{
      {
          k.inlined<graphSpec>(&DurabilityParams::graph),
          k("strata", &DurabilityParams::strata, mapValue<strataSpec>(), "tilted and folded beds"),
          k("joints", &DurabilityParams::joints, listOfMaps<jointSpec>(), "sets of parallel fracture planes")
              .leftOutWhenEmpty(),
          k("rind", &DurabilityParams::rind, mapValue<rindSpec>(), "a case-hardened skin"),
          k("keyframes", &DurabilityParams::keyframes, listOfMaps<keyframeSpec>(), "edits during the run; below")
              .range("in time order"),
      },
      {},
      "([model.md §4](model.md))"};
  return spec;
}

// ---- bubbles and response (docs/model.md §3, §5) ----

const MapSpec<BubbleSpec>& bubbleSphereSpec() {
  static const Keys<BubbleSpec> k;
  static const MapSpec<BubbleSpec> spec{{
      k(
          "radius", [](auto& b) -> auto& { return b.extents[0]; }, length(), "a sphere of offsets")
          .always()
          .unit(kWorld),
  }};
  return spec;
}

const MapSpec<BubbleSpec>& bubbleEllipsoidSpec() {
  static const Keys<BubbleSpec> k;
  static const MapSpec<BubbleSpec> spec{{
      k("radii", &BubbleSpec::extents, lengths3(),
        "an ellipsoid; exaggerates curvature along its short axes (keep them ≥ 6 voxels)")
          .always()
          .unit(kWorld),
  }};
  return spec;
}

const MapSpec<BubbleSpec>& bubbleBoxSpec() {
  static const Keys<BubbleSpec> k;
  static const MapSpec<BubbleSpec> spec{{
      k("half_extents", &BubbleSpec::extents, lengths3(), "a box of offsets").always().unit(kWorld),
  }};
  return spec;
}

const MapSpec<BubbleSpec>& bubbleSpec();

const MapSpec<BubbleSpec::Member>& memberSpec() {
  static const Keys<BubbleSpec::Member> k;
  static const MapSpec<BubbleSpec::Member> spec{{
      k("bubble", &BubbleSpec::Member::bubble, mapValue<bubbleSpec>(), "a member (may itself be a collection)")
          .requiredHere("a collection member needs a bubble")
          .see("bubbles.[].bubble"),
      k("weight", &BubbleSpec::Member::weight, positive(), "the member's weight (normalised)"),
  }};
  return spec;
}

const MapSpec<BubbleSpec>& bubbleSpec() {
  using Kind = BubbleSpec::Kind;
  static const Keys<BubbleSpec> k;
  static const MapSpec<BubbleSpec> spec{
      {
          k.kind(Kind::Sphere, self, mapValue<bubbleSphereSpec>(), "a sphere"),
          k.kind(Kind::Ellipsoid, self, mapValue<bubbleEllipsoidSpec>(), "an ellipsoid"),
          k.kind(Kind::Box, self, mapValue<bubbleBoxSpec>(), "a box"),
          k.kind(Kind::Collection, &BubbleSpec::members,
                 listOfMaps<memberSpec>({"a collection needs at least one member"}),
                 "several bubbles at once: the weighted mean of their exposures")
              .range("at least one member"),
      },
      {kinds(namesOf<Kind>())},
      "A **bubble** is a map with exactly one kind. Every extent must span at least one voxel and at most " +
          formatNumber(kMaxBubbleVoxels) + " voxels at the preset's resolution."};
  return spec;
}

const MapSpec<BubbleBand>& bandSpec() {
  static const Keys<BubbleBand> k;
  static const MapSpec<BubbleBand> spec{
      {
          k("up_to", &BubbleBand::up_to, numberIn(0.0, 1.0, true), "the band's top")
              .requiredHere("a band needs 'up_to' (its top altitude, 0..1)")
              .unit("altitude")
              .range("(0, 1], strictly increasing; the last exactly 1")
              .check(bandsGoUp),
          k("bubble", &BubbleBand::bubble, mapValue<bubbleSpec>(),
            "the neighbourhood whose air share measures exposure")
              .requiredHere("a band needs a 'bubble'")
              .check(bubbleFitsTheGrid),
          k("spheroidal", &BubbleBand::spheroidal, numberIn(0.0, 1e6), "`k_s`: how fast convex rock weathers"),
          k("cavernous", &BubbleBand::cavernous, numberIn(0.0, 1e6), "`k_c`: how fast concave rock weathers"),
      },
      {},
      "A list of bands, bottom to top ([model.md §3](model.md)). Without `bubbles`: one band reaching 1, a "
      "sphere of radius `longest side of grid.size / 16` (kept between 1 and " +
          formatNumber(kMaxBubbleVoxels) + " voxels), `spheroidal: 1`, `cavernous: 0`."};
  return spec;
}

const MapSpec<ResponseParams>& responseSpec() {
  using Kind = ResponseParams::Kind;
  static const Keys<ResponseParams> k;
  static const MapSpec<ResponseParams> spec{
      {
          k.kind(Kind::Power, &ResponseParams::value, positive(), "`f(x) = x^p`; the default is `{power: 1}`"),
          k.kind(Kind::Threshold, &ResponseParams::value, numberIn(0.0, 1.0, false, true),
                 "`f(x) = max(0, (x − t) / (1 − t))`: `0.5` leaves flat rock alone"),
          k.kind(Kind::Curve, &ResponseParams::curve, responseCurve(), "piecewise linear `f`"),
      },
      {kinds(namesOf<Kind>())},
      "Exactly one of `power`, `threshold` and `curve` ([model.md §5](model.md))."};
  return spec;
}

// ---- simulation, mesh, bake, render ----

const MapSpec<GridParams>& gridSpec() {
  static const Keys<GridParams> k;
  static const MapSpec<GridParams> spec{
      {
          k("size", &GridParams::size, lengths3(), "the simulation domain x, y, z; the rock is clipped to it")
              .unit(kWorld)
              .range("each (0, 10⁶]"),
          k("resolution", &GridParams::resolution, integer<int>(GridParams::kMinResolution, GridParams::kMaxResolution),
            "voxels along the longest side of `grid.size`: `h = longest side / resolution`")
              .unit("voxels"),
          k("ground", &GridParams::ground, boolean(),
            "a solid, never-weathering ground below z = 0; `false`: a free-floating rock, rockfall and colluvium off"),
      },
      {},
      "A grid that needs more than 60 % of the machine's memory (or of `ulimit -v`) is refused at "
      "`grid.resolution` ([model.md §1](model.md))."};
  return spec;
}

const MapSpec<RockfallParams>& rockfallSpec() {
  static const Keys<RockfallParams> k;
  static const MapSpec<RockfallParams> spec{
      {
          k("mode", &RockfallParams::mode, choice<RockfallMode>(),
            "rock cut loose falls and stays rock, falls and becomes colluvium, or floats"),
      },
      {},
      "([model.md §6](model.md))"};
  return spec;
}

const MapSpec<ColluviumParams>& colluviumSpec() {
  static const Keys<ColluviumParams> k;
  static const MapSpec<ColluviumParams> spec{
      {
          k("yield", &ColluviumParams::yield, numberIn(0.0, 1.0), "how much of weathered rock piles up")
              .unit("voxels per decimated voxel"),
          k("talus_angle", &ColluviumParams::talus_angle, numberIn(0.0, 90.0, true, true),
            "the steepest slope piles keep")
              .unit(kDegrees),
          k("removal", &ColluviumParams::removal, numberIn(0.0, 1.0),
            "the share of exposed colluvium carried away each cycle")
              .unit("per cycle"),
      },
      {},
      "([model.md §7](model.md))"};
  return spec;
}

const MapSpec<StopParams>& untilSpec() {
  static const Keys<StopParams> k;
  static const MapSpec<StopParams> spec{
      {
          k("rock_volume_fraction", &StopParams::rock_volume_fraction, numberIn(0.0, 1.0, true, true),
            "stop after the first cycle that leaves at most this share of the initial rock"),
      },
      {},
      "([model.md §9](model.md))"};
  return spec;
}

// mesh.sink: a depth, or `suggested`.
Value<double> sinkDepth() {
  return {"number or `suggested`",
          "≥ 0, or `suggested`",
          nullptr,
          false,
          [](const Field& f, double& depth, const ReadContext&) {
            if (f.yaml().IsScalar() && f.yaml().Scalar() == "suggested")
              depth = MeshParams::kSinkSuggested;
            else
              depth = f.numberIn(0.0, kMaxWorldLength);
          },
          [](const double& depth) { return depth < 0 ? json("suggested") : json(depth); }};
}

const MapSpec<MeshParams>& meshSpec() {
  static const Keys<MeshParams> k;
  static const MapSpec<MeshParams> spec{
      {
          k("smoothing", &MeshParams::smoothing, numberIn(0.0, 4.0),
            "smoothing of the voxel surface before polygonising (rounded to whole passes)")
              .unit("Gaussian passes"),
          k("subdivision", &MeshParams::subdivision, integer<int>(0, 3),
            "the most Catmull-Clark levels (OpenSubdiv); fewer where the voxels already carry mesh.detail")
              .unit("levels"),
          k("max_error", &MeshParams::max_error, numberIn(0.0, 8.0, true), "how far LOD0 may leave the refined surface")
              .unit("voxels"),
          k("lods", &MeshParams::lods, lodList(),
            "LOD1, LOD2, …: ratios of LOD0's triangles, or triangle budgets for both surfaces together"),
          k("detail", &MeshParams::detail, mapValue<noiseSpec>(),
            "seeded roughness along the normals before simplification; its `amplitude` is the RMS displacement "
            "on neutral rock, in world units")
              .see("durability.noise.[]"),
          k("apron_toe", &MeshParams::apron_toe, numberIn(0.0, 45.0),
            "the slope the debris apron thins out at towards its rim on the ground; 0 keeps the voxels' rim")
              .unit(kDegrees),
          k("sink", &MeshParams::sink, sinkDepth(),
            "how deep the asset is sunk into the ground: the pivot rises by it; `suggested` sinks it by "
            "`asset.json`'s suggested burial depth")
              .unit(kWorld),
      },
      {},
      "([meshes.md](meshes.md))"};
  return spec;
}

const MapSpec<PaletteLayer>& layerSpec() {
  static const Keys<PaletteLayer> k;
  static const MapSpec<PaletteLayer> spec{{
      k("durability", &PaletteLayer::durability, positive(), "the durability this colour is pinned to")
          .requiredHere("a layer needs durability and color")
          .check(layersSoftToDurable),
      k("color", &PaletteLayer::color, color(), "sRGB").requiredHere("a layer needs durability and color"),
  }};
  return spec;
}

const MapSpec<VertexPaletteParams>& vertexPaletteSpec() {
  static const Keys<VertexPaletteParams> k;
  static const MapSpec<VertexPaletteParams> spec{
      {
          k("palette", &VertexPaletteParams::palette, choice<Palette>(), "how vertex colours are made"),
          k("layers", &VertexPaletteParams::layers, listOfMaps<layerSpec>(),
            "`natural`: colours keyed by durability, interpolated in linear light")
              .range("durability > 0, strictly increasing")
              .defaultIs("`[]`: built-in sandstone"),
          k("colluvium_color", &VertexPaletteParams::colluvium_color, color(), "`natural`: the colluvium's colour")
              .defaultIs("`'#B49A78'` (sandy buff)"),
      },
      {},
      "([meshes.md](meshes.md))"};
  return spec;
}

const MapSpec<RenderParams>& turntableSpec() {
  static const Keys<RenderParams> k;
  static const MapSpec<RenderParams> spec{{
      k("frames", &RenderParams::turntable_frames, integer<int>(0, 360), "views around z (0: no turntable)"),
      k("fps", &RenderParams::turntable_fps, integer<int>(1, 120), "`turntable.mp4`'s frame rate").unit("1/s"),
      k("lookdev", &RenderParams::turntable_lookdev, boolean(),
        "an 18 % grey ball, a colour chart and a three-point rig in frame"),
  }};
  return spec;
}

const MapSpec<RenderParams>& renderSpec() {
  static const Keys<RenderParams> k;
  static const MapSpec<RenderParams> spec{
      {
          k("template", &RenderParams::template_name, templateName(), "the POV-Ray template, by name, never a path"),
          k("width", &RenderParams::width, integer<int>(16, 8192), "image width").unit("pixels"),
          k("height", &RenderParams::height, integer<int>(16, 8192), "image height").unit("pixels"),
          k("quality", &RenderParams::quality, integer<int>(0, 11), "POV-Ray `+Q`"),
          k("antialias", &RenderParams::antialias, numberIn(0.0, 3.0),
            "POV-Ray `+A` threshold; 0 turns antialiasing off"),
          k("turntable", self, mapValue<turntableSpec>(), "views around the rock"),
      },
      {},
      "([rendering.md](rendering.md))"};
  return spec;
}

const MapSpec<CollisionParams>& collisionSpec() {
  static const Keys<CollisionParams> k;
  static const MapSpec<CollisionParams> spec{
      {
          k("max_hulls", &CollisionParams::max_hulls, integer<int>(1, CollisionParams::kMaxHulls),
            "convex hulls per material at most"),
          k("max_vertices", &CollisionParams::max_vertices,
            integer<int>(CollisionParams::kMinVertices, CollisionParams::kMaxVertices),
            "vertices per hull at most (255: PhysX's limit, Unreal's and Unity's)"),
          k("naming", &CollisionParams::naming, choice<HullNaming>(),
            "node names in `collision.glb`: Unreal's `UCX_` or Godot's `-convcolonly`"),
          k("colluvium", &CollisionParams::colluvium, boolean(), "also hull the colluvium, in hulls of its own"),
      },
      {},
      "Written to `collision.glb` when `export` lists `collision` and the bake has meshes "
      "([collision.md](collision.md))."};
  return spec;
}

const MapSpec<DeliveryParams>& deliverySpec() {
  static const Keys<DeliveryParams> k;
  static const MapSpec<DeliveryParams> spec{
      {
          k("profile", &DeliveryParams::profile, choice<DeliveryProfile>(),
            "an engine's conventions: names, the normal map's green channel, hull names, embedded images"),
          k("compressed", &DeliveryParams::compressed, boolean(),
            "also write `compressed/`: KTX2 maps and quantised, meshopt-compressed meshes"),
      },
      {},
      "Where the files go ([delivery.md](delivery.md))."};
  return spec;
}

const MapSpec<TextureParams>& textureSpec() {
  static const Keys<TextureParams> k;
  static const MapSpec<TextureParams> spec{
      {
          k("size", &TextureParams::size, textureSize(), "LOD0's maps' width and height").unit("texels"),
          k("lod_size", &TextureParams::lod_size, choice<LodMapSize>(),
            "`halved`: LOD k's maps at `size / 2^k`, at least 256; `full`: every LOD's at `size`"),
          k("padding", &TextureParams::padding, integer<int>(0, 64),
            "empty texels between charts; every map is dilated into them")
              .unit("texels"),
          k("ao_rays", &TextureParams::ao_rays, integer<int>(1, 1024), "ambient-occlusion rays per vertex")
              .unit("rays"),
          k("ao_distance", &TextureParams::ao_distance, numberIn(0.0, kMaxWorldLength),
            "how far an occlusion ray looks; 0: without limit")
              .unit(kWorld),
          k("cage", &TextureParams::cage, numberIn(0.0, kMaxWorldLength),
            "how far each texel's ray looks for the bake source, both ways along the normal; 0: 5 % of its "
            "bounding-box diagonal")
              .unit(kWorld),
          k("maps", &TextureParams::maps, textureMaps(), "the maps baked; a bake with a `look` adds its History map")
              .defaultIs("all five"),
          k("precision", &TextureParams::precision, choice<MapPrecision>(),
            "`compact`: 8-bit normal maps and a half-float height; `full`: 16-bit normal maps and a 32-bit float "
            "height"),
          k("colour_density", &TextureParams::colour_density, numberIn(0.0, 64.0),
            "texels a voxel the colour maps (base colour, ORM, mask, History) keep at least: each LOD's are halved "
            "while they would keep this many, the normal and height maps staying at the LOD's size; 0: every map "
            "at the LOD's size")
              .unit("texels a voxel"),
      },
      {},
      "([textures.md](textures.md)). Given, even as `texture: {}`, the bake makes a texture set: every LOD "
      "unwrapped, with tangent frames and maps baked from the finest surface into `textures/`; left out (or with "
      "`--no-textures`), none."};
  return spec;
}

const MapSpec<ClastParams>& clastSpec() {
  static const Keys<ClastParams> k;
  static const MapSpec<ClastParams> spec{
      {
          k("count", &ClastParams::count, integer<int>(1, ClastParams::kMaxCount),
            "stones placed on the apron at most (fewer where it has no room)"),
          k("size", &ClastParams::size, interval(0.5, 64.0), "the smallest and largest stone's longest axis")
              .unit("voxels"),
          k("size_exponent", &ClastParams::size_exponent, numberIn(0.0, 4.0, true),
            "`a` in N(> s) ∝ s^-a: how quickly large stones grow rare"),
          k("shapes", &ClastParams::shapes, integer<int>(ClastParams::kMinShapes, ClastParams::kMaxShapes),
            "distinct stone meshes the stones share"),
      },
      {},
      "Stones on the debris apron, each a small weathered rock, larger ones further from the foot "
      "([model.md §13](model.md)); exported as instances of shared meshes. Left out, none."};
  return spec;
}

// ---- the look (docs/textures.md, "The look"; model.md §14) ----

const MapSpec<LookRelief>& reliefSpec() {
  static const Keys<LookRelief> k;
  static const MapSpec<LookRelief> spec{{
      k("amplitude", &LookRelief::amplitude, numberIn(0.0, kMaxWorldLength), "how far the relief stands; 0: none")
          .unit(kWorld),
      k("spacing", &LookRelief::spacing, length(), "the laminae's spacing, the sheets' thickness, the pits' size")
          .unit(kWorld),
  }};
  return spec;
}

const MapSpec<LookParams>& lookColorSpec() {
  static const Keys<LookParams> k;
  static const MapSpec<LookParams> spec{{
      k("stain", &LookParams::stain_color, color(), "the stain water leaves where it runs (sRGB)"),
      k("varnish", &LookParams::varnish_color, color(), "desert varnish or patina on long-exposed rock (sRGB)"),
      k("dust", &LookParams::dust_color, color(), "dust and soil on ledges and in hollows (sRGB)"),
      k("lichen", &LookParams::lichen_color, color(), "lichen on exposed, upward-facing rock (sRGB)"),
  }};
  return spec;
}

const MapSpec<LookParams>& lookSpec() {
  static const Keys<LookParams> k;
  const auto strength = [] { return numberIn(0.0, LookParams::kMaxStrength); };
  static const MapSpec<LookParams> spec{
      {
          k("stain", &LookParams::stain, strength(),
            "streaks where water runs down the fall line and is shed at overhang lips"),
          k("varnish", &LookParams::varnish, strength(), "long-exposed rock darkening towards varnish or patina"),
          k("dust", &LookParams::dust, strength(), "dust and soil on ledges and in upward-facing hollows"),
          k("moisture", &LookParams::moisture, strength(), "a damp band at the foot and in sheltered overhangs"),
          k("scars", &LookParams::scars, strength(), "how much paler fresh rockfall scars and young faces are"),
          k("lichen", &LookParams::lichen, strength(), "lichen on long-exposed, upward-facing rock"),
          k("colors", self, mapValue<lookColorSpec>(), "each effect's colour"),
          k("laminations", &LookParams::laminations, mapValue<reliefSpec>(),
            "ridges and partings along the beds, harder laminae standing out"),
          k("exfoliation", &LookParams::exfoliation, mapValue<reliefSpec>(),
            "sheets parallel to the surface on spheroidally weathered rock (`spacing`: their thickness)"),
          k("pitting", &LookParams::pitting, mapValue<reliefSpec>(),
            "granular pits on cavernously weathered rock (`spacing`: their size)"),
      },
      {},
      "The look made from the rock's weathering history after the simulation "
      "([textures.md](textures.md), [model.md §14](model.md)). Strengths are 0 (off) … 4, 1 the house's. "
      "`look: none` (or no `look`) keeps the palette and its noise alone."};
  return spec;
}

// `look`: a map read by lookSpec, or `none`.
Value<std::optional<LookParams>> lookValue() {
  return {"map or `none`",
          "",
          []() -> const MapInfo& { return lookSpec().info; },
          false,
          [](const Field& f, std::optional<LookParams>& look, const ReadContext& ctx) {
            if (f.yaml().IsScalar() && f.yaml().Scalar() == "none") {
              look.reset();
              return;
            }
            LookParams value;
            readMap(lookSpec(), f, value, nullptr, ctx);
            look = std::move(value);
          },
          [](const std::optional<LookParams>& look) { return look ? writeMap(lookSpec(), *look) : json("none"); }};
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
          k("rockbake", &Preset::schema, schemaVersion(), "the schema version this file is written for")
              .required("missing 'rockbake: 1' (the schema version)"),
          k.refused("extends", "path", refuseExtendsOverride,
                    "a base preset merged under this one ([libraries.md](libraries.md)); a base may extend another"),
          k("name", &Preset::name, assetName(), "the asset's name: its folder `OUT/<name>/` and the name in its files")
              .required("missing 'name' (the asset's name, [a-z0-9_-]+)"),
          k("seed", &Preset::seed, unsigned64(), "every random choice derives from it ([model.md §10](model.md))"),
          k("grid", &Preset::grid, mapValue<gridSpec>(), "the simulation domain"),
          k("shape", &Preset::shape, mapValue<shapeSpec>(), "the initial rock")
              .required("missing 'shape'", "for example shape: {box: {size: [2, 2, 2]}}"),
          k("durability", &Preset::durability, mapValue<durabilitySpec>(), "how hard the rock is"),
          k("family", &Preset::family, mapValue<familySpec>(), "what each seed draws: a different individual")
              .check(familyFitsThePreset),
          k("bubbles", &Preset::bubbles, bandList(), "the bubble graph: how curvature is measured at each altitude")
              .range("at least one band")
              .keyframed(KeyframePart::Bubbles)
              .byDefault(defaultBubbles, "one band, below"),
          k("response", &Preset::response, mapValue<responseSpec>(), "the decimation response `f`")
              .keyframed(KeyframePart::Response)
              .defaultIs("`{power: 1}`"),
          k("rockfall", &Preset::rockfall, mapValue<rockfallSpec>(), "what happens to rock cut loose").resumable(),
          k("colluvium", &Preset::colluvium, mapValue<colluviumSpec>(), "weathered material piling up").resumable(),
          k("time", stopTime, positive(), "how long to weather: `⌈time / h⌉` cycles, the same rock at any resolution")
              .check(timeWithinCycleLimit)
              .resumable()
              .unit("time (world units of retreat)")
              .range("> 0, at most " + docWhole(kMaxCycles) + " cycles at the resolution"),
          k("cycles", stopCycles, integer<int>(1, kMaxCycles), "how many cycles to run (resolution dependent)")
              .resumable(),
          k("until", &Preset::stop, mapValue<untilSpec>(), "stop early").leftOutWhenEmpty().resumable(),
          k("mesh", &Preset::mesh, mapValue<meshSpec>(), "extraction, subdivision, detail, LODs"),
          k("bake", &Preset::bake, mapValue<vertexPaletteSpec>(), "palettes: the colours baked into the meshes"),
          k("export", &Preset::exports, exportFormats(),
            "the files a bake writes ([formats.md](formats.md)); LODs come with `glb`, `collision.glb` with "
            "`collision`"),
          k("collision", &Preset::collision, mapValue<collisionSpec>(), "convex hulls a game engine collides with"),
          k("tags", &Preset::tags, tagList(), "`asset.json`'s tags (a tag given twice is kept once)"),
          k("units_per_meter", &Preset::units_per_meter, numberIn(0.0, 1e6, true),
            "world units per metre: the GLBs are written in metres (glTF's unit), `asset.json` gives sizes in "
            "metres"),
          k("delivery", &Preset::delivery, mapValue<deliverySpec>(), "an engine profile and a compressed set"),
          k("render", &Preset::render, mapValue<renderSpec>(), "the POV-Ray render"),
          k("texture", &Preset::texture, mapValue<textureSpec>(), "the texture set: UV atlases and baked maps"),
          k("clasts", &Preset::clasts, mapValue<clastSpec>(), "stones on the debris apron"),
          k("look", &Preset::look, lookValue(),
            "what the weathering history makes of the surface: stains, "
            "varnish, dust, moisture, scars, laminations, exfoliation, pitting"),
      },
      {exactlyOne({"time", "cycles"}, "missing 'time' (or 'cycles')", "give either 'time' or 'cycles', not both",
                  "time: T runs ceil(T / voxel size) cycles, the same rock at any resolution")},
      "Exactly one of `time` and `cycles` ([model.md §9](model.md)). The file is at most 1 MiB of YAML holding "
      "one document, a map. Control characters other than tab, line feed and carriage return are refused (shown "
      "escaped in the message).",
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
