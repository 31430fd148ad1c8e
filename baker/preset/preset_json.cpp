#include "preset/preset_json.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

namespace rockbake {
namespace {

using nlohmann::json;

json bubbleToJson(const BubbleSpec& b) {
  switch (b.kind) {
    case BubbleSpec::Kind::Sphere:
      return {{"sphere", {{"radius", b.extents[0]}}}};
    case BubbleSpec::Kind::Ellipsoid:
      return {{"ellipsoid", {{"radii", b.extents}}}};
    case BubbleSpec::Kind::Box:
      return {{"box", {{"half_extents", b.extents}}}};
    case BubbleSpec::Kind::Collection: {
      json members = json::array();
      for (const auto& m : b.members) members.push_back({{"bubble", bubbleToJson(m.bubble)}, {"weight", m.weight}});
      return {{"collection", members}};
    }
  }
  return nullptr;
}

json graphToJson(const DurabilityGraph& g) {
  json out = {{"points", g.points}};
  json noise = json::array();
  for (const auto& n : g.noise)
    noise.push_back(n ? json{{"amplitude", n->amplitude}, {"period", n->period}, {"octaves", n->octaves}}
                      : json(nullptr));
  out["noise"] = noise;
  return out;
}

json bandsToJson(const std::vector<BubbleBand>& bubbles) {
  json bands = json::array();
  for (const auto& b : bubbles)
    bands.push_back({{"up_to", b.up_to},
                     {"bubble", bubbleToJson(b.bubble)},
                     {"spheroidal", b.spheroidal},
                     {"cavernous", b.cavernous}});
  return bands;
}

json responseToJson(const ResponseParams& r) {
  switch (r.kind) {
    case ResponseParams::Kind::Power:
      return {{"power", r.value}};
    case ResponseParams::Kind::Threshold:
      return {{"threshold", r.value}};
    case ResponseParams::Kind::Curve:
      return {{"curve", r.curve}};
  }
  return nullptr;
}

json shapeToJson(const ShapeParams& shape) {
  struct Visitor {
    json operator()(const BoxShape& b) const { return {{"box", {{"size", b.size}}}}; }
    json operator()(const CylinderShape& c) const {
      return {{"cylinder", {{"radius", c.radius}, {"height", c.height}}}};
    }
    json operator()(const SphereShape& s) const { return {{"sphere", {{"radius", s.radius}}}}; }
    json operator()(const InsideCornerShape& c) const {
      return {{"inside_corner", {{"size", c.size}, {"wall", c.wall}}}};
    }
    json operator()(const ImageShape& i) const {
      return {{"image",
               {{"path", i.path.string()},
                {"mode", i.mode == ImageMode::Revolve ? "revolve" : "extrude"},
                {"height", i.height}}}};
    }
    json operator()(const MeshShape& m) const { return {{"mesh", {{"path", m.path.string()}, {"scale", m.scale}}}}; }
  };
  json out = std::visit(Visitor{}, shape.kind);
  out["center"] = shape.center ? json(*shape.center) : json(nullptr);
  // Only when given, so presets without it keep their fingerprint.
  if (const auto& v = shape.variation)
    out["variation"] = {{"amplitude", v->amplitude}, {"period", v->period}, {"octaves", v->octaves}};
  return out;
}

const char* paletteName(Palette p) {
  switch (p) {
    case Palette::Natural:
      return "natural";
    case Palette::Debug:
      return "debug";
    case Palette::Curvature:
      return "curvature";
  }
  return "natural";
}

const char* rockfallName(RockfallMode m) {
  switch (m) {
    case RockfallMode::Drop:
      return "drop";
    case RockfallMode::Crumble:
      return "crumble";
    case RockfallMode::Off:
      return "off";
  }
  return "drop";
}

}  // namespace

json presetToJson(const Preset& p) {
  json out;
  out["rockbake"] = p.schema;
  out["name"] = p.name;
  out["seed"] = p.seed;
  out["grid"] = {{"size", p.grid.size}, {"resolution", p.grid.resolution}, {"ground", p.grid.ground}};
  out["shape"] = shapeToJson(p.shape);
  json durability = graphToJson(p.durability.graph);
  json keyframes = json::array();
  for (const auto& k : p.durability.keyframes) {
    // Only the parts the keyframe carries (a graph-only keyframe reads as it always has).
    json kf = k.graph ? graphToJson(*k.graph) : json::object();
    kf["at"] = k.at;
    if (k.bubbles) kf["bubbles"] = bandsToJson(*k.bubbles);
    if (k.response) kf["response"] = responseToJson(*k.response);
    keyframes.push_back(kf);
  }
  durability["keyframes"] = keyframes;
  // Geology only when given, so presets without it keep their fingerprint.
  if (const auto& s = p.durability.strata)
    durability["strata"] = {{"dip", s->dip},
                            {"strike", s->strike},
                            {"warp", {{"amplitude", s->warp_amplitude}, {"period", s->warp_period}}}};
  if (!p.durability.joints.empty()) {
    json joints = json::array();
    for (const auto& j : p.durability.joints)
      joints.push_back({{"strike", j.strike},
                        {"dip", j.dip},
                        {"spacing", j.spacing},
                        {"jitter", j.jitter},
                        {"width", j.width},
                        {"factor", j.factor}});
    durability["joints"] = joints;
  }
  if (const auto& r = p.durability.rind) durability["rind"] = {{"depth", r->depth}, {"factor", r->factor}};
  out["durability"] = durability;
  out["bubbles"] = bandsToJson(p.bubbles);
  out["response"] = responseToJson(p.response);
  out["rockfall"] = {{"mode", rockfallName(p.rockfall.mode)}};
  out["colluvium"] = {
      {"yield", p.colluvium.yield}, {"talus_angle", p.colluvium.talus_angle}, {"removal", p.colluvium.removal}};
  if (p.stop.time) out["time"] = *p.stop.time;
  if (p.stop.cycles) out["cycles"] = *p.stop.cycles;
  if (p.stop.rock_volume_fraction) out["until"] = {{"rock_volume_fraction", *p.stop.rock_volume_fraction}};
  out["mesh"] = {{"smoothing", p.mesh.smoothing},
                 {"subdivision", p.mesh.subdivision},
                 {"max_error", p.mesh.max_error},
                 {"lods", p.mesh.lods}};
  if (p.mesh.detail)
    out["mesh"]["detail"] = {{"amplitude", p.mesh.detail->amplitude},
                             {"period", p.mesh.detail->period},
                             {"octaves", p.mesh.detail->octaves}};
  json layers = json::array();
  for (const auto& l : p.bake.layers) layers.push_back({{"durability", l.durability}, {"color", l.color}});
  out["bake"] = {{"palette", paletteName(p.bake.palette)}, {"layers", layers}};
  if (p.bake.colluvium_color) out["bake"]["colluvium_color"] = *p.bake.colluvium_color;
  out["export"] = p.exports;
  out["tags"] = p.tags;
  out["units_per_meter"] = p.units_per_meter;
  out["render"] = {{"template", p.render.template_name}, {"width", p.render.width},
                   {"height", p.render.height},          {"quality", p.render.quality},
                   {"antialias", p.render.antialias},    {"turntable", {{"frames", p.render.turntable_frames}}}};
  // The movie's rate and the look-dev set matter only with a turntable; without
  // one they stay out, so that the input hashes of bakes without a turntable
  // are what they were before the keys existed.
  if (p.render.turntable_frames > 0) {
    out["render"]["turntable"]["fps"] = p.render.turntable_fps;
    out["render"]["turntable"]["lookdev"] = p.render.turntable_lookdev;
  }
  return out;
}

}  // namespace rockbake
