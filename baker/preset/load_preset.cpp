// Preset loading: parse (yaml-cpp) → apply --set overrides → validate into
// plain data. Every read goes through a Field that knows its key path and
// source position, so every error can say where it is.
#include "preset/load_preset.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <tuple>

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include "core/did_you_mean.h"
#include "core/error.h"
#include "preset/render_templates.h"
#include "preset/yaml_field.h"
#include "preset/yaml_text.h"

namespace rockbake {
namespace {

// ---- --set ----

// `origin` is what messages name as the override's location: "--set <argument>" by default.
void applyOverride(YAML::Node& root, const std::string& argument, const std::string& origin, Source& source) {
  const auto bad = [&](const std::string& problem, const std::string& hint = {}) {
    throw InputError({origin.empty() ? "--set" : origin}, "", "'" + argument + "': " + problem, hint);
  };
  const std::size_t equals = argument.find('=');
  if (equals == std::string::npos || equals == 0)
    bad("expected key.path=VALUE", "for example --set colluvium.yield=0.3 or --set bubbles.0.spheroidal=0.5");
  const std::string path = argument.substr(0, equals);
  YAML::Node value;
  try {
    value = YAML::Load(argument.substr(equals + 1));
  } catch (const YAML::Exception& e) {
    bad("the value is not valid YAML: " + e.msg);
  }
  std::vector<std::string> keys;
  std::stringstream stream(path);
  for (std::string key; std::getline(stream, key, '.');) {
    if (key.empty()) bad("the key path has an empty part");
    keys.push_back(key);
  }
  if (keys.empty()) bad("the key path is empty");

  YAML::Node node;
  node.reset(root);
  for (std::size_t i = 0; i < keys.size(); ++i) {
    const std::string& key = keys[i];
    const bool last = i + 1 == keys.size();
    YAML::Node next;
    if (node.IsSequence()) {
      const bool digits = std::all_of(key.begin(), key.end(), [](unsigned char c) { return std::isdigit(c); });
      std::size_t index = std::numeric_limits<std::size_t>::max();
      if (!digits) bad("'" + key + "' must be a list index (0, 1, ...) at that point");
      try {
        index = std::stoul(key);
      } catch (const std::out_of_range&) {
        // leave it past the end
      }
      if (index >= node.size()) bad("index " + key + " is past the end of a list of " + std::to_string(node.size()));
      if (last) {
        node[index] = value;
        break;
      }
      next.reset(node[index]);
    } else {
      if (!node.IsMap() && !node.IsNull()) bad("'" + key + "' cannot be set inside a value that is not a map");
      if (last) {
        node[key] = value;
        break;
      }
      if (!node[key].IsDefined() || node[key].IsNull()) node[key] = YAML::Node(YAML::NodeType::Map);
      next.reset(node[key]);
    }
    node.reset(next);
  }
  // `time` and `cycles` are alternatives: setting one replaces the other.
  if (keys.size() == 1 && (keys[0] == "time" || keys[0] == "cycles"))
    root.remove(keys[0] == "time" ? "cycles" : "time");
  source.overrides.emplace_back(path, origin.empty() ? "--set " + argument : origin);
}

// ---- sections ----

// An sRGB colour: "#rrggbb" or [r, g, b] with each in [0, 1].
SrgbColor readColor(const Field& f) {
  if (f.isSequence()) {
    if (f.size() != 3) f.fail("expected [r, g, b] (sRGB, each 0..1) or \"#rrggbb\"");
    return {f.item(0).numberIn(0.0, 1.0), f.item(1).numberIn(0.0, 1.0), f.item(2).numberIn(0.0, 1.0)};
  }
  const std::string text = f.string();
  const bool hex = text.size() == 7 && text[0] == '#' &&
                   std::all_of(text.begin() + 1, text.end(), [](char c) { return std::isxdigit((unsigned char)c); });
  if (!hex) f.fail("'" + text + "' is not a colour", "write \"#rrggbb\" (sRGB) or [r, g, b] with each 0..1");
  SrgbColor rgb;
  for (int i = 0; i < 3; ++i)
    rgb[std::size_t(i)] = std::stoi(text.substr(1 + 2 * std::size_t(i), 2), nullptr, 16) / 255.0;
  return rgb;
}

BubbleSpec readBubble(const Field& f) {
  BubbleSpec bubble;
  const std::string kind = f.oneOf({"sphere", "ellipsoid", "box", "collection"});
  const Field k = f.at(kind);
  if (kind == "sphere") {
    k.expectMap();
    bubble.kind = BubbleSpec::Kind::Sphere;
    bubble.extents = {k.at("radius").length(), 0, 0};
  } else if (kind == "ellipsoid") {
    k.expectMap();
    bubble.kind = BubbleSpec::Kind::Ellipsoid;
    bubble.extents = k.at("radii").positiveVec3();
  } else if (kind == "box") {
    k.expectMap();
    bubble.kind = BubbleSpec::Kind::Box;
    bubble.extents = k.at("half_extents").positiveVec3();
  } else {
    bubble.kind = BubbleSpec::Kind::Collection;
    if (k.size() == 0) k.fail("a collection needs at least one member");
    for (std::size_t i = 0; i < k.size(); ++i) {
      const Field m = k.item(i);
      m.expectMap();
      if (!m.has("bubble")) m.fail("a collection member needs a bubble");
      bubble.members.push_back({readBubble(m.at("bubble")), m.has("weight") ? m.at("weight").positive() : 1.0});
    }
  }
  return bubble;
}

// Bubble extents in voxels: below one the bubble is the voxel itself and measures nothing; above
// kMaxBubbleVoxels a cycle costs too much.
constexpr double kMaxBubbleVoxels = 48.0;

// Every bubble extent must span at least a voxel and stay affordable. `f` is the bubble's map.
void checkBubbleSize(const BubbleSpec& bubble, const Field& f, double h) {
  constexpr double kMaxVoxels = kMaxBubbleVoxels;
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
    if (voxels > kMaxVoxels)
      extent.fail("a bubble extent of " + formatNumber(bubble.extents[std::size_t(a)]) + " spans " +
                      formatNumber(std::round(voxels)) + " voxels; at most " + formatNumber(kMaxVoxels) +
                      " are allowed",
                  "make the bubble smaller or lower grid.resolution");
  }
}

std::vector<std::array<double, 2>> readPoints(const Field& f) {
  std::vector<std::array<double, 2>> points;
  const std::size_t n = f.size();
  if (n == 0) f.fail("needs at least one [altitude, durability] point");
  for (std::size_t i = 0; i < n; ++i) {
    const Field p = f.item(i);
    if (p.size() != 2) p.fail("expected [altitude, durability]");
    const double a = p.item(0).numberIn(0.0, 1.0);
    const double d = p.item(1).positive();
    if (!points.empty() && a <= points.back()[0])
      p.item(0).fail("altitudes must increase along the list (" + formatNumber(a) + " follows " +
                     formatNumber(points.back()[0]) + ")");
    points.push_back({a, d});
  }
  return points;
}

// Reads points and noise of a graph's map (the durability section or a keyframe).
DurabilityGraph readGraph(const Field& f) {
  f.expectMap();
  DurabilityGraph graph;
  if (f.has("points")) graph.points = readPoints(f.at("points"));
  if (f.has("noise")) {
    const Field n = f.at("noise");
    const std::size_t segments = graph.points.size() - 1;
    if (n.size() != segments && n.size() != 0)  // [] means no noise anywhere
      n.fail("needs one entry per segment: " + std::to_string(segments) + " for " +
                 std::to_string(graph.points.size()) + " points, found " + std::to_string(n.size()),
             "use null for a segment without noise");
    for (std::size_t i = 0; i < n.size(); ++i) {
      const Field s = n.item(i);
      if (!s.defined()) {
        graph.noise.push_back(std::nullopt);
        continue;
      }
      s.expectMap();
      NoiseParams noise;
      if (s.has("amplitude")) noise.amplitude = s.at("amplitude").numberIn(0.0, 1e6);
      if (s.has("period")) noise.period = s.at("period").length();
      if (s.has("octaves")) noise.octaves = int(s.at("octaves").integer(1, 8));
      graph.noise.push_back(noise);
    }
  }
  return graph;
}

// Runs one part of the validation: a problem is recorded (with where its reading stopped) and the
// next part goes on, so one run lists every problem; loading then reports the first.
template <typename Read>
void validatePart(const Source& source, Read&& read) {
  try {
    read();
  } catch (const InputError& e) {
    source.reads->failed.push_back(e.keyPath());
    source.problems->push_back(e);
  }
}

// The bubble graph: bands bottom to top, the last reaching 1.
std::vector<BubbleBand> readBands(const Field& bands, double h, const Source& source) {
  std::vector<BubbleBand> out;
  if (bands.size() == 0) bands.fail("needs at least one band");
  // Band by band, so that linting lists the problems of every band.
  for (std::size_t i = 0; i < bands.size(); ++i)
    validatePart(source, [&] {
      const Field b = bands.item(i);
      b.expectMap();
      BubbleBand band;
      if (!b.has("up_to")) b.fail("a band needs 'up_to' (its top altitude, 0..1)");
      band.up_to = b.at("up_to").numberIn(0.0, 1.0, true, false);
      if (!out.empty() && band.up_to <= out.back().up_to)
        b.at("up_to").fail("bands go bottom to top: up_to must increase");
      if (!b.has("bubble")) b.fail("a band needs a 'bubble'");
      band.bubble = readBubble(b.at("bubble"));
      checkBubbleSize(band.bubble, b.at("bubble"), h);
      if (b.has("spheroidal")) band.spheroidal = b.at("spheroidal").numberIn(0.0, 1e6);
      if (b.has("cavernous")) band.cavernous = b.at("cavernous").numberIn(0.0, 1e6);
      out.push_back(band);
    });
  if (out.size() == bands.size() && out.back().up_to != 1.0)
    bands.item(bands.size() - 1).at("up_to").fail("the last band must reach 1 (the top of grid.size)");
  return out;
}

// The decimation response: power, threshold or curve.
ResponseParams readResponse(const Field& r) {
  const std::string kind = r.oneOf({"power", "threshold", "curve"});
  if (kind == "power") return {ResponseParams::Kind::Power, r.at("power").positive(), {}};
  if (kind == "threshold")
    return {ResponseParams::Kind::Threshold, r.at("threshold").numberIn(0.0, 1.0, false, true), {}};
  ResponseParams response;
  const Field c = r.at("curve");
  response.kind = ResponseParams::Kind::Curve;
  for (std::size_t i = 0; i < c.size(); ++i) {
    const Field pt = c.item(i);
    if (pt.size() != 2) pt.fail("expected [x, y]");
    const double x = pt.item(0).numberIn(0.0, 1.0), y = pt.item(1).numberIn(0.0, 1.0);
    if (!response.curve.empty() && x <= response.curve.back()[0]) pt.item(0).fail("x must increase along the curve");
    response.curve.push_back({x, y});
  }
  if (response.curve.size() < 2 || response.curve.front()[0] != 0.0 || response.curve.back()[0] != 1.0)
    c.fail("the curve must start at x = 0 and end at x = 1");
  return response;
}

// shape.variation (docs/model.md §8).
ShapeVariation readVariation(const Field& f) {
  f.expectMap();
  ShapeVariation v;
  v.amplitude =
      f.require("amplitude", "a variation needs 'amplitude' (world units; 0 keeps the shape)").numberIn(0.0, 1e6);
  if (f.has("period")) v.period = f.at("period").positive();
  if (f.has("octaves")) v.octaves = int(f.at("octaves").integer(1, 8));
  return v;
}

// durability.strata, joints and rind (docs/model.md §4).
StrataParams readStrata(const Field& f) {
  f.expectMap();
  StrataParams s;
  if (f.has("dip")) s.dip = f.at("dip").numberIn(0.0, 90.0);
  if (f.has("strike")) s.strike = f.at("strike").numberIn(-360.0, 360.0);
  if (f.has("warp")) {
    const Field w = f.at("warp");
    w.expectMap();
    s.warp_amplitude = w.require("amplitude", "a warp needs 'amplitude' (world units)").numberIn(0.0, 1e6);
    s.warp_period = w.require("period", "a warp needs 'period' (world units)").positive();
  }
  return s;
}

JointSet readJointSet(const Field& f) {
  f.expectMap();
  JointSet j;
  if (f.has("strike")) j.strike = f.at("strike").numberIn(-360.0, 360.0);
  if (f.has("dip")) j.dip = f.at("dip").numberIn(0.0, 90.0);
  j.spacing = f.require("spacing", "a joint set needs 'spacing' (world units between its planes)").positive();
  if (f.has("jitter")) {
    j.jitter = f.at("jitter").number();
    if (j.jitter < 0 || j.jitter >= j.spacing)
      f.at("jitter").fail("must be at least 0 and less than spacing (" + formatNumber(j.spacing) + "), found " +
                          formatNumber(j.jitter));
  }
  j.width = f.require("width", "a joint set needs 'width' (world units either side of a plane)").positive();
  if (j.width >= j.spacing)
    f.at("width").fail("must be less than spacing (" + formatNumber(j.spacing) + "), found " + formatNumber(j.width),
                       "a joint zone as wide as the spacing leaves no sound rock between the planes");
  j.factor = f.require("factor", "a joint set needs 'factor' (the durability multiplier at a plane, > 0)").positive();
  return j;
}

RindParams readRind(const Field& f) {
  f.expectMap();
  RindParams r;
  r.depth = f.require("depth", "a rind needs 'depth' (world units below the initial surface)").positive();
  r.factor = f.require("factor", "a rind needs 'factor' (how many times as durable, > 0)").positive();
  return r;
}

void readShape(const Field& f, Preset& p) {
  f.has("center");  // asked first, so that they are known even when the kind is missing
  f.has("variation");
  const std::string kind = f.oneOf({"box", "cylinder", "sphere", "inside_corner", "image", "mesh"});
  const Field k = f.at(kind);
  if (kind == "box") {
    k.expectMap();
    p.shape.kind = BoxShape{k.at("size").positiveVec3()};
  } else if (kind == "cylinder") {
    k.expectMap();
    p.shape.kind = CylinderShape{k.at("radius").length(), k.at("height").length()};
  } else if (kind == "sphere") {
    k.expectMap();
    p.shape.kind = SphereShape{k.at("radius").length()};
  } else if (kind == "inside_corner") {
    k.expectMap();
    InsideCornerShape corner{k.at("size").positiveVec3(), k.at("wall").length()};
    if (corner.wall >= std::min(corner.size[0], corner.size[1]))
      k.at("wall").fail("must be thinner than the corner's footprint (" + formatNumber(corner.size[0]) + " × " +
                        formatNumber(corner.size[1]) + ")");
    p.shape.kind = corner;
  } else if (kind == "image") {
    k.expectMap();
    ImageShape image;
    const std::filesystem::path given = k.at("path").string();
    image.path =
        std::filesystem::absolute(given.is_absolute() ? given : k.at("path").folder() / given).lexically_normal();
    std::error_code unreadable;  // e.g. a name too long for the file system: no file, not a crash
    if (!std::filesystem::is_regular_file(image.path, unreadable))
      k.at("path").fail("no image file at " + image.path.string(), k.at("path").relativePathHint());
    image.mode = (k.has("mode") ? k.at("mode").choice({"extrude", "revolve"}) : "extrude") == "revolve"
                     ? ImageMode::Revolve
                     : ImageMode::Extrude;
    image.height = k.at("height").length();
    p.shape.kind = image;
  } else {
    k.expectMap();
    MeshShape mesh;
    const std::filesystem::path given = k.at("path").string();
    mesh.path =
        std::filesystem::absolute(given.is_absolute() ? given : k.at("path").folder() / given).lexically_normal();
    std::error_code unreadable;
    if (!std::filesystem::is_regular_file(mesh.path, unreadable))
      k.at("path").fail("no mesh file at " + mesh.path.string(), k.at("path").relativePathHint());
    if (k.has("scale")) mesh.scale = k.at("scale").numberIn(0.0, kMaxWorldLength, true);
    p.shape.kind = mesh;
  }
  if (f.has("center")) p.shape.center = f.at("center").vec3();
  if (f.has("variation")) p.shape.variation = readVariation(f.at("variation"));
}

// Reads every part of the schema; each problem goes to source.problems (unknown keys first,
// in reading order, then the others in reading order), and reading goes on.
Preset validate(const YAML::Node& root_node, Source& source, const std::filesystem::path& file) {
  ReadLog reads;
  source.reads = &reads;
  const Field root(root_node, "", source);
  Preset p;
  p.file = file;
  validatePart(source, [&] { root.expectMap(); });
  validatePart(source, [&] {
    const Field version = root.require("rockbake", "missing 'rockbake: 1' (the schema version)");
    const long long schema =
        version.integer(std::numeric_limits<long long>::min(), std::numeric_limits<long long>::max());
    if (schema != 1)
      version.fail("schema version " + std::to_string(schema) + " is not supported; this rockbake reads version 1",
                   "write rockbake: 1, or use the rockbake the preset was written for");
    p.schema = 1;
  });
  // The files' `extends` were merged before the overrides; only an override can bring one back.
  validatePart(source, [&] {
    if (root.has("extends"))
      root.at("extends").fail("extends cannot be overridden", "name the base preset in the preset file");
  });

  validatePart(source, [&] {
    p.name = root.require("name", "missing 'name' (the asset's name, [a-z0-9_-]+)").string();
    if (const auto problem = assetNameProblem(p.name)) root.at("name").fail(*problem, "it names the output folder");
  });
  validatePart(source, [&] {
    if (root.has("seed")) p.seed = root.at("seed").unsigned64();
  });

  validatePart(source, [&] {
    if (!root.has("grid")) return;
    const Field g = root.at("grid");
    g.expectMap();
    if (g.has("size")) p.grid.size = g.at("size").positiveVec3();
    if (g.has("resolution"))
      p.grid.resolution = int(g.at("resolution").integer(GridParams::kMinResolution, GridParams::kMaxResolution));
    if (g.has("ground")) p.grid.ground = g.at("ground").boolean();
  });
  const double h = std::max({p.grid.size[0], p.grid.size[1], p.grid.size[2]}) / p.grid.resolution;

  validatePart(source, [&] {
    readShape(root.require("shape", "missing 'shape'", "for example shape: {box: {size: [2, 2, 2]}}"), p);
  });

  validatePart(source, [&] {
    if (!root.has("durability")) return;
    const Field d = root.at("durability");
    p.durability.graph = readGraph(d);
    if (d.has("strata")) p.durability.strata = readStrata(d.at("strata"));
    if (d.has("joints")) {
      const Field js = d.at("joints");
      for (std::size_t i = 0; i < js.size(); ++i) p.durability.joints.push_back(readJointSet(js.item(i)));
    }
    if (d.has("rind")) p.durability.rind = readRind(d.at("rind"));
    if (d.has("keyframes")) {
      const Field ks = d.at("keyframes");
      for (std::size_t i = 0; i < ks.size(); ++i) {
        const Field k = ks.item(i);
        DurabilityKeyframe keyframe;
        const DurabilityGraph graph = readGraph(k);
        if (!k.has("at")) k.fail("a keyframe needs 'at' (the simulation time it takes effect)");
        if (!k.has("points") && !k.has("bubbles") && !k.has("response"))
          k.fail("a keyframe needs 'points' (the graph it switches to), 'bubbles' or 'response'");
        if (k.has("noise") && !k.has("points")) k.at("noise").fail("noise needs the keyframe's 'points'");
        if (k.has("points")) keyframe.graph = graph;
        if (k.has("bubbles")) keyframe.bubbles = readBands(k.at("bubbles"), h, source);
        if (k.has("response")) keyframe.response = readResponse(k.at("response"));
        keyframe.at = k.at("at").numberIn(0.0, 1e9);
        if (!p.durability.keyframes.empty() && keyframe.at < p.durability.keyframes.back().at)
          k.at("at").fail("keyframes must be in time order");
        p.durability.keyframes.push_back(keyframe);
      }
    }
  });

  validatePart(source, [&] {
    if (!root.has("bubbles")) return;
    p.bubbles = readBands(root.at("bubbles"), h, source);
  });
  if (!root.has("bubbles")) {
    // One band, a sphere of a sixteenth of the longest side: a moderate, resolution-independent default,
    // kept within what a bubble may span so a preset without bubbles bakes at every allowed resolution
    // (it is 0.5 voxels at resolution 8 and 128 at 2048).
    BubbleBand band;
    band.bubble.kind = BubbleSpec::Kind::Sphere;
    const double radius = std::max({p.grid.size[0], p.grid.size[1], p.grid.size[2]}) / 16.0;
    band.bubble.extents = {std::clamp(radius, h, kMaxBubbleVoxels * h), 0, 0};
    p.bubbles = {band};
  }

  validatePart(source, [&] {
    if (!root.has("response")) return;
    p.response = readResponse(root.at("response"));
  });

  validatePart(source, [&] {
    if (!root.has("rockfall")) return;
    const Field r = root.at("rockfall");
    r.expectMap();
    if (r.has("mode")) {
      const std::string mode = r.at("mode").choice({"drop", "crumble", "off"});
      p.rockfall.mode = mode == "drop"      ? RockfallMode::Drop
                        : mode == "crumble" ? RockfallMode::Crumble
                                            : RockfallMode::Off;
    }
  });
  validatePart(source, [&] {
    if (!root.has("colluvium")) return;
    const Field c = root.at("colluvium");
    c.expectMap();
    if (c.has("yield")) p.colluvium.yield = c.at("yield").numberIn(0.0, 1.0);
    if (c.has("talus_angle")) p.colluvium.talus_angle = c.at("talus_angle").numberIn(0.0, 90.0, true, true);
    if (c.has("removal")) p.colluvium.removal = c.at("removal").numberIn(0.0, 1.0);
  });

  validatePart(source, [&] {
    if (root.has("time") == root.has("cycles"))
      root.fail(root.has("time") ? "give either 'time' or 'cycles', not both" : "missing 'time' (or 'cycles')",
                "time: T runs ceil(T / voxel size) cycles, the same rock at any resolution");
    if (root.has("time")) {
      // `time` runs ceil(time / h) cycles: the same limit as `cycles`.
      p.stop.time = root.at("time").positive();
      const double cycles = std::ceil(*p.stop.time / h - 1e-9);
      if (cycles > double(kMaxCycles))
        root.at("time").fail("time " + formatNumber(*p.stop.time) + " is " +
                                 (cycles < 1e15 ? std::to_string((long long)cycles) : formatNumber(cycles)) +
                                 " cycles at this resolution (a cycle is " + formatNumber(h) +
                                 " units of time); at most " + std::to_string(kMaxCycles) + " cycles are allowed",
                             "lower time (at most " + formatNumber(double(kMaxCycles) * h) + " here)");
    }
    if (root.has("cycles")) p.stop.cycles = int(root.at("cycles").integer(1, kMaxCycles));
  });
  validatePart(source, [&] {
    if (!root.has("until")) return;
    const Field u = root.at("until");
    u.expectMap();
    if (u.has("rock_volume_fraction"))
      p.stop.rock_volume_fraction = u.at("rock_volume_fraction").numberIn(0.0, 1.0, true, true);
  });

  validatePart(source, [&] {
    if (!root.has("mesh")) return;
    const Field m = root.at("mesh");
    m.expectMap();
    if (m.has("smoothing")) p.mesh.smoothing = m.at("smoothing").numberIn(0.0, 4.0);
    if (m.has("subdivision")) p.mesh.subdivision = int(m.at("subdivision").integer(0, 3));
    if (m.has("max_error")) p.mesh.max_error = m.at("max_error").numberIn(0.0, 8.0, true);
    if (m.has("lods")) {
      const Field l = m.at("lods");
      p.mesh.lods.clear();
      for (std::size_t i = 0; i < l.size(); ++i) {
        const Field item = l.item(i);
        const double v = item.numberIn(0.0, 1e9, true);
        const bool count = v >= 1.0;
        if (count && v != std::floor(v))
          item.fail("a LOD is a ratio in (0, 1) of LOD0's triangles or a whole triangle count, not " +
                    fmt::format("{}", v));
        if (!p.mesh.lods.empty() && (p.mesh.lods.back() >= 1.0) != count)
          item.fail("mix of ratios and triangle counts", "give every LOD as a ratio or every LOD as a triangle count");
        if (!p.mesh.lods.empty() && v >= p.mesh.lods.back())
          item.fail(count ? "LOD triangle counts must decrease" : "LOD ratios must decrease");
        p.mesh.lods.push_back(v);
      }
    }
    if (m.has("detail")) {
      const Field d = m.at("detail");
      if (d.defined()) {
        d.expectMap();
        NoiseParams detail;
        if (d.has("amplitude")) detail.amplitude = d.at("amplitude").numberIn(0.0, 1e6);
        if (d.has("period")) detail.period = d.at("period").positive();
        if (d.has("octaves")) detail.octaves = int(d.at("octaves").integer(1, 8));
        p.mesh.detail = detail;
      } else {
        p.mesh.detail.reset();
      }
    }
  });
  validatePart(source, [&] {
    if (!root.has("bake")) return;
    const Field b = root.at("bake");
    b.expectMap();
    if (b.has("palette")) {
      const std::string palette = b.at("palette").choice({"natural", "debug", "curvature"});
      p.bake.palette = palette == "natural" ? Palette::Natural
                       : palette == "debug" ? Palette::Debug
                                            : Palette::Curvature;
    }
    if (b.has("layers")) {
      const Field layers = b.at("layers");
      for (std::size_t i = 0; i < layers.size(); ++i) {
        const Field l = layers.item(i);
        l.expectMap();
        if (!l.has("durability") || !l.has("color")) l.fail("a layer needs durability and color");
        const PaletteLayer layer{l.at("durability").positive(), readColor(l.at("color"))};
        if (!p.bake.layers.empty() && layer.durability <= p.bake.layers.back().durability)
          l.at("durability").fail("layers go from soft to durable: durability must increase");
        p.bake.layers.push_back(layer);
      }
    }
    if (b.has("colluvium_color")) p.bake.colluvium_color = readColor(b.at("colluvium_color"));
  });
  validatePart(source, [&] {
    if (!root.has("export")) return;
    const Field e = root.at("export");
    p.exports.clear();
    for (std::size_t i = 0; i < e.size(); ++i) {
      const std::string format = e.item(i).choice({"ply", "obj", "glb", "vdb"});
      if (std::find(p.exports.begin(), p.exports.end(), format) != p.exports.end())
        e.item(i).fail("'" + format + "' is listed twice");
      p.exports.push_back(format);
    }
  });
  validatePart(source, [&] {
    if (!root.has("tags")) return;
    const Field t = root.at("tags");
    for (std::size_t i = 0; i < t.size(); ++i) {
      const std::string tag = t.item(i).string();
      if (!isAssetName(tag)) t.item(i).fail("tag '" + tag + "' may only use a-z, 0-9, '_' and '-'");
      if (std::find(p.tags.begin(), p.tags.end(), tag) == p.tags.end()) p.tags.push_back(tag);
    }
  });
  validatePart(source, [&] {
    if (root.has("units_per_meter")) p.units_per_meter = root.at("units_per_meter").numberIn(0.0, 1e6, true);
  });
  validatePart(source, [&] {
    if (!root.has("render")) return;
    const Field r = root.at("render");
    r.expectMap();
    if (r.has("template")) {
      p.render.template_name = r.at("template").string();
      if (const auto problem = renderTemplateProblem(p.render.template_name, renderTemplatesDir()))
        r.at("template")
            .fail(*problem, "a template is named by its file in " + renderTemplatesDir().string() +
                                " without .pov, never by a path");
    }
    if (r.has("width")) p.render.width = int(r.at("width").integer(16, 8192));
    if (r.has("height")) p.render.height = int(r.at("height").integer(16, 8192));
    if (r.has("quality")) p.render.quality = int(r.at("quality").integer(0, 11));
    if (r.has("antialias")) p.render.antialias = r.at("antialias").numberIn(0.0, 3.0);
    if (r.has("turntable")) {
      const Field t = r.at("turntable");
      t.expectMap();
      if (t.has("frames")) p.render.turntable_frames = int(t.at("frames").integer(0, 360));
      if (t.has("fps")) p.render.turntable_fps = int(t.at("fps").integer(1, 120));
      if (t.has("lookdev")) p.render.turntable_lookdev = t.at("lookdev").boolean();
    }
  });

  // A key no read asked for is unknown; it often explains a problem reported beside it.
  std::vector<InputError> unknown = unreadKeyProblems(source);
  source.problems->insert(source.problems->begin(), unknown.begin(), unknown.end());
  source.reads = nullptr;
  return p;
}

// ---- reading files, extends ----

SourceLocation locationOf(const std::string& file, const YAML::Mark& mark) {
  if (mark.is_null()) return {file, 0, 0};
  return {file, mark.line + 1, mark.column + 1};
}

std::optional<std::string> readText(const std::filesystem::path& file) {
  return readYamlFile(file.string(), "a preset");
}

// The one YAML document of a preset file (`file` names it in messages).
YAML::Node readDocument(const std::string& yaml_text, const std::string& file) {
  return loadYamlDocument(yaml_text, file, "a preset");
}

bool sameFile(const std::filesystem::path& a, const std::filesystem::path& b) {
  std::error_code error_a, error_b;
  const auto canonical_a = std::filesystem::weakly_canonical(a, error_a);
  const auto canonical_b = std::filesystem::weakly_canonical(b, error_b);
  return (error_a ? a : canonical_a) == (error_b ? b : canonical_b);
}

// Keys a preset gives that replace more of its base than themselves. Alternatives (`time` or `cycles`,
// the shape's kind, the response's kind): choosing one drops the base's choice, which would otherwise
// be merged in beside it and refused. New durability points drop the base's noise, one entry per
// segment of the base's points.
struct MergeRule {
  const char* path;                     // the map the rule applies to
  std::vector<std::string> when_given;  // when the preset gives any of these keys there,
  std::vector<std::string> drops;       // these keys of the base are not inherited
};
const std::vector<MergeRule>& mergeRules() {
  static const std::vector<std::string> shapes = {"box", "cylinder", "sphere", "inside_corner", "image", "mesh"};
  static const std::vector<std::string> responses = {"power", "threshold", "curve"};
  static const std::vector<MergeRule> rules = {{"", {"time", "cycles"}, {"time", "cycles"}},
                                               {"shape", shapes, shapes},
                                               {"response", responses, responses},
                                               {"durability", {"points"}, {"noise"}}};
  return rules;
}

// `child_keys`: the keys the preset itself gives in the map at `path`.
bool droppedByMergeRule(const std::vector<std::string>& child_keys, const std::string& path, const std::string& key) {
  const auto contains = [](const std::vector<std::string>& keys, const std::string& k) {
    return std::find(keys.begin(), keys.end(), k) != keys.end();
  };
  for (const auto& rule : mergeRules())
    if (rule.path == path && contains(rule.drops, key))
      for (const auto& given : rule.when_given)
        if (contains(child_keys, given)) return true;
  return false;
}

// Copies the base's keys the child does not have into the child (maps deep-merged, the child's keys win;
// lists and scalars replaced whole; mergeRules()) and records which file each copied key path came from.
void mergeBase(YAML::Node child, const YAML::Node& base, const std::string& path, std::vector<Origin>& origins,
               const std::vector<Origin>& base_origins) {
  std::vector<std::string> child_keys;
  for (const auto& entry : child)
    if (entry.first.IsScalar()) child_keys.push_back(entry.first.Scalar());
  std::vector<std::pair<std::string, YAML::Mark>> seen;
  for (const auto& entry : base) {
    const std::string& base_file = originOf(base_origins, path).file;
    if (!entry.first.IsScalar())
      throw InputError(locationOf(base_file, entry.first.Mark()), path,
                       "expected a key name, found " + describe(entry.first));
    const std::string key = entry.first.Scalar();
    const std::string key_path = path.empty() ? key : path + "." + key;
    // Both of a repeated key would merge into one: report it as loading a single file does.
    const auto first = std::find_if(seen.begin(), seen.end(), [&](const auto& s) { return s.first == key; });
    if (first != seen.end())
      throw InputError(locationOf(originOf(base_origins, key_path).file, entry.first.Mark()), key_path,
                       "'" + key + "' is given twice (first on line " + std::to_string(first->second.line + 1) + ")",
                       "keep one of them");
    seen.emplace_back(key, entry.first.Mark());

    std::optional<YAML::Node> mine;
    for (auto child_entry : child)
      if (child_entry.first.IsScalar() && child_entry.first.Scalar() == key) {
        mine = child_entry.second;
        break;
      }
    if (!mine) {
      if (droppedByMergeRule(child_keys, path, key)) continue;
      child[key] = entry.second;
      origins.push_back({key_path, originOf(base_origins, key_path).file, originOf(base_origins, key_path).folder});
      for (const auto& origin : base_origins)
        if (origin.key_path.size() > key_path.size() && underKeyPath(origin.key_path, key_path))
          origins.push_back(origin);
    } else if (mine->IsMap() && entry.second.IsMap()) {
      mergeBase(*mine, entry.second, key_path, origins, base_origins);
    }
  }
}

// Replaces `root`'s `extends` by the merged base chain. `file` is absolute; `name` names it in messages;
// `chain` collects the files read, this one first. `origins` receives which file wrote each key path.
void resolveExtends(YAML::Node root, const std::string& name, const std::filesystem::path& file,
                    std::vector<std::filesystem::path>& chain, std::vector<Origin>& origins) {
  namespace fs = std::filesystem;
  origins = {{"", name, file.parent_path()}};
  chain.push_back(file);
  std::optional<YAML::Node> value;
  YAML::Mark key_mark;
  for (const auto& entry : root)
    if (entry.first.IsScalar() && entry.first.Scalar() == "extends") {
      value = entry.second;
      key_mark = entry.first.Mark();
      break;
    }
  if (!value) return;
  const SourceLocation here =
      locationOf(name, value->IsDefined() && !value->IsNull() && !value->Mark().is_null() ? value->Mark() : key_mark);
  if (!value->IsScalar() || value->Scalar().empty())
    throw InputError(here, "extends", "expected the path of a base preset, found " + describe(*value),
                     "for example extends: base.yaml (relative to this file)");
  const fs::path written = value->Scalar();
  const fs::path base_file = (written.is_absolute() ? written : file.parent_path() / written).lexically_normal();
  const std::string base_name =
      written.is_absolute() ? written.string() : (fs::path(name).parent_path() / written).lexically_normal().string();

  for (const auto& earlier : chain)
    if (sameFile(earlier, base_file)) {
      std::string cycle;
      for (const auto& f : chain) cycle += f.lexically_relative(chain.front().parent_path()).string() + " → ";
      cycle += base_file.lexically_relative(chain.front().parent_path()).string();
      throw InputError(here, "extends", "the base presets form a cycle: " + cycle, "remove one of these extends");
    }

  const std::optional<std::string> text = readText(base_file);
  if (!text)
    throw InputError(here, "extends", "no base preset at " + base_file.string(),
                     "extends paths are relative to the folder of " + name);
  YAML::Node base;
  try {
    base = readDocument(*text, base_name);
  } catch (const InputError& e) {
    throw InputError(here, "extends", "cannot use the base preset: " + std::string(e.what()));
  }
  if (!base.IsMap())
    throw InputError(here, "extends", "the base preset " + base_name + " is not a YAML map (key: value, ...)");

  std::vector<Origin> base_origins;
  resolveExtends(base, base_name, base_file, chain, base_origins);
  root.remove("extends");
  mergeBase(root, base, "", origins, base_origins);
}

// A preset read, merged with its bases and overridden, before validation.
struct PresetTree {
  YAML::Node root;
  Source source;
  std::vector<std::filesystem::path> files;  // the preset, then its bases
};

PresetTree readPresetTree(const std::string& yaml_text, const std::filesystem::path& file,
                          const PresetOverrides& overrides) {
  PresetTree tree;
  const std::string name = file.string();
  tree.root = readDocument(yaml_text, name);
  if (!tree.root.IsMap()) throw InputError({name, 1, 1}, "", "a preset must be a YAML map (key: value, ...)");
  resolveExtends(tree.root, name, std::filesystem::absolute(file).lexically_normal(), tree.files, tree.source.origins);

  YAML::Node& root = tree.root;
  Source& source = tree.source;
  for (std::size_t i = 0; i < overrides.sets.size(); ++i)
    applyOverride(root, overrides.sets[i], i < overrides.set_origins.size() ? overrides.set_origins[i] : "", source);
  if (overrides.seed) {
    root["seed"] = *overrides.seed;
    source.overrides.emplace_back("seed", "--seed " + std::to_string(*overrides.seed));
  }
  if (overrides.resolution) {
    if (!root["grid"].IsDefined() || root["grid"].IsNull()) root["grid"] = YAML::Node(YAML::NodeType::Map);
    if (root["grid"].IsMap()) root["grid"]["resolution"] = *overrides.resolution;
    source.overrides.emplace_back("grid.resolution", "--resolution " + std::to_string(*overrides.resolution));
  }
  return tree;
}

std::string readPresetFile(const std::filesystem::path& file) {
  const std::optional<std::string> text = readText(file);
  if (!text) throw InputError({file.string()}, "", "cannot read the preset file", "check the path");
  return *text;
}

}  // namespace

Preset parsePreset(const std::string& yaml_text, const std::filesystem::path& file, const PresetOverrides& overrides) {
  PresetTree tree = readPresetTree(yaml_text, file, overrides);
  std::map<std::string, SourceLocation> locations;
  std::vector<InputError> problems;
  tree.source.locations = &locations;
  tree.source.problems = &problems;
  Preset preset = validate(tree.root, tree.source, std::filesystem::absolute(file));
  if (!problems.empty()) throw problems.front();
  preset.sources = std::move(tree.files);
  preset.locations = std::move(locations);
  return preset;
}

Preset loadPreset(const std::filesystem::path& file, const PresetOverrides& overrides) {
  return parsePreset(readPresetFile(file), file, overrides);
}

std::vector<InputError> lintPreset(const std::filesystem::path& file, const PresetOverrides& overrides) {
  std::vector<InputError> problems;
  std::vector<std::string> files;  // in chain order, to list problems file by file
  try {
    PresetTree tree = readPresetTree(readPresetFile(file), file, overrides);
    for (const auto& origin : tree.source.origins)
      if (std::find(files.begin(), files.end(), origin.file) == files.end()) files.push_back(origin.file);
    tree.source.problems = &problems;
    validate(tree.root, tree.source, std::filesystem::absolute(file));
  } catch (const InputError& e) {
    problems.push_back(e);
  }
  const auto rank = [&](const InputError& e) {
    return std::tuple(std::size_t(std::find(files.begin(), files.end(), e.where().file) - files.begin()),
                      e.where().line, e.where().column);
  };
  std::stable_sort(problems.begin(), problems.end(),
                   [&](const InputError& a, const InputError& b) { return rank(a) < rank(b); });
  return problems;
}

}  // namespace rockbake
