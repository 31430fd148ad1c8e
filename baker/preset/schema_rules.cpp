#include "preset/schema_rules.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "preset/render_templates.h"
#include "preset/yaml_text.h"

namespace rockbake::schema {
namespace {

template <class T>
Value<T> custom(std::string type, std::string range, std::function<void(const Field&, T&, const ReadContext&)> read) {
  return {std::move(type), std::move(range), nullptr, false, std::move(read), toJson<T>};
}

// An [a, b] pair, a in [0, 1]; `pair` names it in the problem ("[altitude, durability]").
std::array<double, 2> readPair(const Field& p, const char* pair, double (*second)(const Field&)) {
  if (p.size() != 2) p.fail(std::string("expected ") + pair);
  const double a = p.item(0).numberIn(0.0, 1.0);
  return {a, second(p.item(1))};
}

// Every bubble extent must span at least a voxel and stay affordable. `f` is the bubble's map.
void checkBubbleSize(const BubbleSpec& bubble, const Field& f, double h) {
  if (bubble.kind == BubbleSpec::Kind::Collection) {
    for (std::size_t i = 0; i < bubble.members.size(); ++i)
      checkBubbleSize(bubble.members[i].bubble, f.at("collection").item(i).at("bubble"), h);
    return;
  }
  const int axes = bubble.kind == BubbleSpec::Kind::Sphere ? 1 : 3;
  for (int a = 0; a < axes; ++a) {
    const double voxels = bubble.extents[std::size_t(a)] / h;
    const Field extent = bubble.kind == BubbleSpec::Kind::Sphere      ? f.at("sphere").at("radius")
                         : bubble.kind == BubbleSpec::Kind::Ellipsoid ? f.at("ellipsoid").at("radii").item(a)
                                                                      : f.at("box").at("half_extents").item(a);
    if (voxels < 1.0)
      extent.fail("a bubble extent of " + formatNumber(bubble.extents[std::size_t(a)]) +
                      " is smaller than one voxel (" + formatNumber(h) + " at this resolution)",
                  "make the bubble larger or raise grid.resolution");
    if (voxels > kMaxBubbleVoxels)
      extent.fail("a bubble extent of " + formatNumber(bubble.extents[std::size_t(a)]) + " spans " +
                      formatNumber(std::round(voxels)) + " voxels; at most " + formatNumber(kMaxBubbleVoxels) +
                      " are allowed",
                  "make the bubble smaller or lower grid.resolution");
  }
}

}  // namespace

// ---- values ----

Value<int> schemaVersion() {
  return custom<int>("whole number", "`1`", [](const Field& version, int& schema, const ReadContext&) {
    const long long given =
        version.integer(std::numeric_limits<long long>::min(), std::numeric_limits<long long>::max());
    if (given != 1)
      version.fail("schema version " + std::to_string(given) + " is not supported; this rockbake reads version 1",
                   "write rockbake: 1, or use the rockbake the preset was written for");
    schema = 1;
  });
}

Value<std::string> assetName() {
  return custom<std::string>("name", "", [](const Field& f, std::string& name, const ReadContext&) {
    name = f.string();
    if (const auto problem = assetNameProblem(name)) f.fail(*problem, "it names the output folder");
  });
}

Value<std::filesystem::path> existingFile(std::string what, std::string range) {
  Value<std::filesystem::path> value = {
      "path",
      std::move(range),
      nullptr,
      false,
      [what](const Field& f, std::filesystem::path& path, const ReadContext&) {
        const std::filesystem::path given = f.string();
        path = std::filesystem::absolute(given.is_absolute() ? given : f.folder() / given).lexically_normal();
        std::error_code unreadable;  // e.g. a name too long for the file system: no file, not a crash
        if (!std::filesystem::is_regular_file(path, unreadable))
          f.fail("no " + what + " file at " + path.string(), f.relativePathHint());
      },
      [](const std::filesystem::path& path) { return json(path.string()); }};
  return value;
}

Value<std::vector<std::array<double, 2>>> altitudePoints() {
  return custom<std::vector<std::array<double, 2>>>(
      "list of `[altitude, durability]`", "at least one point; altitude [0, 1], strictly increasing; durability > 0",
      [](const Field& f, std::vector<std::array<double, 2>>& points, const ReadContext&) {
        points.clear();
        const std::size_t n = f.size();
        if (n == 0) f.fail("needs at least one [altitude, durability] point");
        for (std::size_t i = 0; i < n; ++i) {
          const Field p = f.item(i);
          const auto point = readPair(p, "[altitude, durability]", [](const Field& d) { return d.positive(); });
          if (!points.empty() && point[0] <= points.back()[0])
            p.item(0).fail("altitudes must increase along the list (" + formatNumber(point[0]) + " follows " +
                           formatNumber(points.back()[0]) + ")");
          points.push_back(point);
        }
      });
}

Value<std::vector<std::array<double, 2>>> responseCurve() {
  return custom<std::vector<std::array<double, 2>>>(
      "list of `[x, y]`",
      "at least two points; x in [0, 1], strictly increasing, from exactly 0 to exactly 1; y in [0, 1]",
      [](const Field& c, std::vector<std::array<double, 2>>& curve, const ReadContext&) {
        curve.clear();
        for (std::size_t i = 0; i < c.size(); ++i) {
          const Field pt = c.item(i);
          const auto point = readPair(pt, "[x, y]", [](const Field& y) { return y.numberIn(0.0, 1.0); });
          if (!curve.empty() && point[0] <= curve.back()[0]) pt.item(0).fail("x must increase along the curve");
          curve.push_back(point);
        }
        if (curve.size() < 2 || curve.front()[0] != 0.0 || curve.back()[0] != 1.0)
          c.fail("the curve must start at x = 0 and end at x = 1");
      });
}

Value<std::vector<double>> lodList() {
  return custom<std::vector<double>>(
      "list of numbers", "each (0, 10⁹]; all ratios (< 1) or all whole triangle counts (≥ 1); strictly decreasing",
      [](const Field& l, std::vector<double>& lods, const ReadContext&) {
        lods.clear();
        for (std::size_t i = 0; i < l.size(); ++i) {
          const Field item = l.item(i);
          const double v = item.numberIn(0.0, 1e9, true);
          const bool count = v >= 1.0;
          if (count && v != std::floor(v))
            item.fail("a LOD is a ratio in (0, 1) of LOD0's triangles or a whole triangle count, not " +
                      fmt::format("{}", v));
          if (!lods.empty() && (lods.back() >= 1.0) != count)
            item.fail("mix of ratios and triangle counts",
                      "give every LOD as a ratio or every LOD as a triangle count");
          if (!lods.empty() && v >= lods.back())
            item.fail(count ? "LOD triangle counts must decrease" : "LOD ratios must decrease");
          lods.push_back(v);
        }
      });
}

Value<SrgbColor> color() {
  return custom<SrgbColor>("colour", "", [](const Field& f, SrgbColor& rgb, const ReadContext&) {
    if (f.isSequence()) {
      if (f.size() != 3) f.fail("expected [r, g, b] (sRGB, each 0..1) or \"#rrggbb\"");
      rgb = {f.item(0).numberIn(0.0, 1.0), f.item(1).numberIn(0.0, 1.0), f.item(2).numberIn(0.0, 1.0)};
      return;
    }
    const std::string text = f.string();
    const bool hex = text.size() == 7 && text[0] == '#' &&
                     std::all_of(text.begin() + 1, text.end(), [](char c) { return std::isxdigit((unsigned char)c); });
    if (!hex) f.fail("'" + text + "' is not a colour", "write \"#rrggbb\" (sRGB) or [r, g, b] with each 0..1");
    for (std::size_t i = 0; i < 3; ++i) rgb[i] = std::stoi(text.substr(1 + 2 * i, 2), nullptr, 16) / 255.0;
  });
}

Value<std::vector<std::string>> exportFormats() {
  static const std::vector<std::string> kFormats = {"ply", "obj", "glb", "vdb", "collision"};
  return custom<std::vector<std::string>>("list", "each `ply`, `obj`, `glb`, `vdb` or `collision`, none twice",
                                          [](const Field& e, std::vector<std::string>& exports, const ReadContext&) {
                                            exports.clear();
                                            for (std::size_t i = 0; i < e.size(); ++i) {
                                              const std::string format = e.item(i).choice(kFormats);
                                              if (std::find(exports.begin(), exports.end(), format) != exports.end())
                                                e.item(i).fail("'" + format + "' is listed twice");
                                              exports.push_back(format);
                                            }
                                          });
}

Value<std::vector<std::string>> tagList() {
  return custom<std::vector<std::string>>("list of names", "",
                                          [](const Field& t, std::vector<std::string>& tags, const ReadContext&) {
                                            tags.clear();
                                            for (std::size_t i = 0; i < t.size(); ++i) {
                                              const std::string tag = t.item(i).string();
                                              if (!isAssetName(tag))
                                                t.item(i).fail("tag '" + tag + "' may only use a-z, 0-9, '_' and '-'");
                                              if (std::find(tags.begin(), tags.end(), tag) == tags.end())
                                                tags.push_back(tag);
                                            }
                                          });
}

Value<std::string> templateName() {
  return custom<std::string>("name", "a template in `render_templates/` (or `$ROCKBAKE_RENDER_TEMPLATES`)",
                             [](const Field& f, std::string& name, const ReadContext&) {
                               name = f.string();
                               if (const auto problem = renderTemplateProblem(name, renderTemplatesDir()))
                                 f.fail(*problem, "a template is named by its file in " +
                                                      renderTemplatesDir().string() + " without .pov, never by a path");
                             });
}

Value<int> textureSize() {
  return custom<int>("whole number", "a power of two, 256 … 8192", [](const Field& f, int& size, const ReadContext&) {
    size = int(f.integer(256, 8192));
    if ((size & (size - 1)) != 0)
      f.fail(std::to_string(size) + " is not a power of two", "use 256, 512, 1024, 2048, 4096 or 8192");
  });
}

Value<std::vector<TextureMap>> textureMaps() {
  std::string names;
  for (const auto& name : namesOf<TextureMap>()) names += (names.empty() ? "`" : ", `") + name + "`";
  return {"list",
          "each " + names + ", none twice, at least one",
          nullptr,
          false,
          [](const Field& l, std::vector<TextureMap>& maps, const ReadContext&) {
            maps.clear();
            if (l.size() == 0) l.fail("lists no map", "list at least one, or bake with --no-textures to make none");
            for (std::size_t i = 0; i < l.size(); ++i) {
              const TextureMap map = *valueNamed<TextureMap>(l.item(i).choice(namesOf<TextureMap>()));
              if (std::find(maps.begin(), maps.end(), map) != maps.end())
                l.item(i).fail("'" + std::string(nameOf(map)) + "' is listed twice");
              maps.push_back(map);
            }
          },
          [](const std::vector<TextureMap>& maps) {
            json out = json::array();
            for (TextureMap map : maps) out.push_back(nameOf(map));
            return out;
          }};
}

// The files' `extends` were merged before the overrides; only an override can bring one back.
namespace {
// Two numbers, the first not above the second; `read` reads and checks each.
template <class T, class Read>
std::array<T, 2> readInterval(const Field& f, Read&& read) {
  if (!f.isSequence() || f.size() != 2) f.fail("expected [min, max], found " + describe(f.yaml()));
  const std::array<T, 2> v{read(f.item(0)), read(f.item(1))};
  if (v[0] > v[1])
    f.fail("min " + formatNumber(double(v[0])) + " is greater than max " + formatNumber(double(v[1])),
           "write the smaller bound first");
  return v;
}
std::string intervalRange(double lo, double hi, bool lo_open) {
  return std::string(lo_open ? "(" : "[") + docNumber(lo) + ", " + docNumber(hi) + "], min ≤ max";
}
}  // namespace

Value<Interval> interval(double lo, double hi, bool lo_open) {
  return custom<Interval>("[min, max]", intervalRange(lo, hi, lo_open),
                          [=](const Field& f, Interval& v, const ReadContext&) {
                            v = readInterval<double>(f, [&](const Field& x) { return x.numberIn(lo, hi, lo_open); });
                          });
}

Value<std::array<int, 2>> wholeInterval(int lo, int hi) {
  return custom<std::array<int, 2>>("[min, max]", docWhole(lo) + " … " + docWhole(hi) + ", min ≤ max",
                                    [=](const Field& f, std::array<int, 2>& v, const ReadContext&) {
                                      v = readInterval<int>(f, [&](const Field& x) { return int(x.integer(lo, hi)); });
                                    });
}

Value<std::array<Interval, 3>> axisIntervals(double lo, double hi) {
  return custom<std::array<Interval, 3>>(
      "3 × [min, max]", intervalRange(lo, hi, true) + ", for x, y, z",
      [=](const Field& f, std::array<Interval, 3>& v, const ReadContext&) {
        if (!f.isSequence()) f.fail("expected three [min, max] ranges (x, y, z), found " + describe(f.yaml()));
        if (f.size() != 3)
          f.fail("expected three [min, max] ranges (x, y, z), found " + std::to_string(f.size()));
        for (std::size_t a = 0; a < 3; ++a)
          v[a] = readInterval<double>(f.item(a), [&](const Field& x) { return x.numberIn(lo, hi, true); });
      });
}

void refuseExtendsOverride(const Field& extends) {
  extends.fail("extends cannot be overridden", "name the base preset in the preset file");
}

// ---- checks ----

void oneNoisePerSegment(const Field& graph, const DurabilityGraph& g, const DurabilityGraph*, const ReadContext&) {
  const Field n = graph.at("noise");
  const std::size_t segments = g.points.size() - 1;
  if (n.size() != segments && n.size() != 0)  // [] means no noise anywhere
    n.fail("needs one entry per segment: " + std::to_string(segments) + " for " + std::to_string(g.points.size()) +
               " points, found " + std::to_string(n.size()),
           "use null for a segment without noise");
}

void familyFitsThePreset(const Field& root, const Preset& p, const Preset*, const ReadContext&) {
  if (!p.family) return;
  if (p.shape.center)
    root.at("family").fail(
        "a family fits the grid to each individual and places the shape itself, so "
        "shape.center cannot be given with it",
        "remove shape.center, or remove family to place the shape yourself");
  if (p.family->fracture && p.family->fracture->cuts[1] > 0 && p.durability.joints.empty())
    root.at("family")
        .at("fracture")
        .fail(
            "a family's fracture cuts along the preset's joint sets, and "
            "durability.joints has none",
            "add durability.joints, or remove family.fracture");
}

void wallThinnerThanFootprint(const Field& corner, const InsideCornerShape& c, const InsideCornerShape*,
                              const ReadContext&) {
  if (c.wall >= std::min(c.size[0], c.size[1]))
    corner.at("wall").fail("must be thinner than the corner's footprint (" + formatNumber(c.size[0]) + " × " +
                           formatNumber(c.size[1]) + ")");
}

void jitterBelowSpacing(const Field& joint, const JointSet& j, const JointSet*, const ReadContext&) {
  if (j.jitter < 0 || j.jitter >= j.spacing)
    joint.at("jitter").fail("must be at least 0 and less than spacing (" + formatNumber(j.spacing) + "), found " +
                            formatNumber(j.jitter));
}

void widthBelowSpacing(const Field& joint, const JointSet& j, const JointSet*, const ReadContext&) {
  if (j.width >= j.spacing)
    joint.at("width").fail(
        "must be less than spacing (" + formatNumber(j.spacing) + "), found " + formatNumber(j.width),
        "a joint zone as wide as the spacing leaves no sound rock between the planes");
}

void keyframeChangesSomething(const Field& k, const DurabilityKeyframe&, const DurabilityKeyframe*,
                              const ReadContext&) {
  if (!k.has("points") && !k.has("bubbles") && !k.has("response"))
    k.fail("a keyframe needs 'points' (the graph it switches to), 'bubbles' or 'response'");
}

void noiseNeedsPoints(const Field& k, const DurabilityKeyframe&, const DurabilityKeyframe*, const ReadContext&) {
  if (k.has("noise") && !k.has("points")) k.at("noise").fail("noise needs the keyframe's 'points'");
}

void keyframesInTimeOrder(const Field& k, const DurabilityKeyframe& keyframe, const DurabilityKeyframe* previous,
                          const ReadContext&) {
  if (previous && keyframe.at < previous->at) k.at("at").fail("keyframes must be in time order");
}

void bandsGoUp(const Field& b, const BubbleBand& band, const BubbleBand* previous, const ReadContext&) {
  if (previous && band.up_to <= previous->up_to) b.at("up_to").fail("bands go bottom to top: up_to must increase");
}

void bubbleFitsTheGrid(const Field& b, const BubbleBand& band, const BubbleBand*, const ReadContext& ctx) {
  checkBubbleSize(band.bubble, b.at("bubble"), ctx.h());
}

void lastBandReachesTheTop(const Field& bands, const std::vector<BubbleBand>& read) {
  if (read.back().up_to != 1.0)
    bands.item(read.size() - 1).at("up_to").fail("the last band must reach 1 (the top of grid.size)");
}

void layersSoftToDurable(const Field& l, const PaletteLayer& layer, const PaletteLayer* previous, const ReadContext&) {
  if (previous && layer.durability <= previous->durability)
    l.at("durability").fail("layers go from soft to durable: durability must increase");
}

// `time` runs ceil(time / h) cycles: the same limit as `cycles`.
void timeWithinCycleLimit(const Field& root, const Preset& p, const Preset*, const ReadContext& ctx) {
  const double h = ctx.h();
  const double cycles = std::ceil(*p.stop.time / h - 1e-9);
  if (cycles > double(kMaxCycles))
    root.at("time").fail("time " + formatNumber(*p.stop.time) + " is " +
                             (cycles < 1e15 ? std::to_string((long long)cycles) : formatNumber(cycles)) +
                             " cycles at this resolution (a cycle is " + formatNumber(h) + " units of time); at most " +
                             std::to_string(kMaxCycles) + " cycles are allowed",
                         "lower time (at most " + formatNumber(double(kMaxCycles) * h) + " here)");
}

// A moderate, resolution-independent default, kept within what a bubble may span so that a preset
// without bubbles bakes at every allowed resolution (it is 0.5 voxels at resolution 8 and 128 at 2048).
void defaultBubbles(Preset& p, const ReadContext& ctx) {
  BubbleBand band;
  band.bubble.kind = BubbleSpec::Kind::Sphere;
  const double radius = std::max({p.grid.size[0], p.grid.size[1], p.grid.size[2]}) / 16.0;
  band.bubble.extents = {std::clamp(radius, ctx.h(), kMaxBubbleVoxels * ctx.h()), 0, 0};
  p.bubbles = {band};
}

}  // namespace rockbake::schema
