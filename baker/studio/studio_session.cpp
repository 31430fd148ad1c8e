#include "studio/studio_session.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <regex>
#include <sstream>

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include "core/error.h"
#include "export/vdb_file.h"
#include "pipeline/manifest.h"
#include "pipeline/preview_mesh.h"
#include "pipeline/read_inputs.h"
#include "platform/atomic_file.h"
#include "platform/memory.h"
#include "preset/keyframe_edit.h"
#include "preset/load_preset.h"
#include "preset/preset_json.h"
#include "preset/schema.h"
#include "preset/yaml_text.h"
#include "sim/grid_layout.h"
#include "sim/response.h"
#include "sim/shapes.h"

namespace rockbake {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// Past the preset's end the studio may run this many more cycles (run_until, seek).
constexpr int kMaxExtraCycles = 10000;
// In-memory checkpoints on the timeline: about this many over the preset's time.
constexpr int kCheckpointsPerRun = 16;
// Samples of the response function f in the state (x = 0, 1/64, ..., 1).
constexpr int kResponseSamples = 64;

// The preset's text, read as `lint` and `bake` read a preset (preset/yaml_text.h):
// a FIFO, a device or a file over 1 MiB is refused before it is read.
std::string readPresetText(const fs::path& file) {
  std::optional<std::string> text = readYamlFile(file.string(), "a preset");
  if (!text) throw InputError({file.string()}, "", "cannot read the preset file", "check the path");
  return std::move(*text);
}

// A JSON value as a YAML node. Numbers are written in their shortest exact
// form, so a saved keyframe time reads back as the same double.
YAML::Node toYaml(const json& j) {
  switch (j.type()) {
    case json::value_t::object: {
      YAML::Node map(YAML::NodeType::Map);
      for (const auto& [key, value] : j.items()) map[key] = toYaml(value);
      return map;
    }
    case json::value_t::array: {
      YAML::Node list(YAML::NodeType::Sequence);
      bool numbers = true;
      for (const auto& value : j) {
        list.push_back(toYaml(value));
        numbers = numbers && (value.is_number() || (value.is_array() && value.size() <= 3));
      }
      if (numbers) list.SetStyle(YAML::EmitterStyle::Flow);
      return list;
    }
    case json::value_t::number_float:
      return YAML::Node(fmt::format("{}", j.get<double>()));
    case json::value_t::number_integer:
    case json::value_t::number_unsigned:
      return YAML::Node(j.dump());
    case json::value_t::boolean:
      return YAML::Node(j.get<bool>() ? "true" : "false");
    case json::value_t::string:
      return YAML::Node(j.get<std::string>());
    default:
      return YAML::Node(YAML::NodeType::Null);
  }
}

// durability {points, noise}, bubbles and response of a preset, in its JSON (= YAML) form.
json graphJson(const Preset& p, const DurabilityGraph& graph) {
  Preset copy = p;
  copy.durability.graph = graph;
  copy.durability.keyframes.clear();
  json d = presetToJson(copy)["durability"];
  json out = {{"points", d["points"]}};
  if (!graph.noise.empty()) out["noise"] = d["noise"];
  return out;
}

void appendU32(std::string& out, std::uint32_t v) {
  char bytes[4];
  std::memcpy(bytes, &v, 4);  // little-endian machines only, as the page reads it
  out.append(bytes, 4);
}

void appendMesh(std::string& out, const SurfaceMesh& m) {
  std::vector<std::array<std::uint32_t, 3>> triangles = m.triangles;
  for (const auto& q : m.quads) {
    triangles.push_back({q[0], q[1], q[2]});
    triangles.push_back({q[0], q[2], q[3]});
  }
  appendU32(out, std::uint32_t(m.positions.size()));
  appendU32(out, std::uint32_t(triangles.size()));
  out.append(reinterpret_cast<const char*>(m.positions.data()), m.positions.size() * sizeof(m.positions[0]));
  std::vector<std::array<float, 3>> colours = m.colors;
  colours.resize(m.positions.size(), {0.6f, 0.6f, 0.6f});
  out.append(reinterpret_cast<const char*>(colours.data()), colours.size() * sizeof(colours[0]));
  out.append(reinterpret_cast<const char*>(triangles.data()), triangles.size() * sizeof(triangles[0]));
}

}  // namespace

StudioSession::StudioSession(const fs::path& preset_file, int resolution, CheckpointBounds checkpoint_bounds)
    : file_(preset_file),
      original_text_(readPresetText(preset_file)),
      resolution_(resolution),
      checkpoints_(checkpoint_bounds) {
  own_resolution_ = parsePreset(original_text_, file_).grid.resolution;
  preset_ = parsePreset(original_text_, file_, {{}, std::nullopt, resolution_});
  shape_ = readInputs(preset_);
  restart();
}

StudioSession::~StudioSession() = default;

SimParams StudioSession::simParams() const {
  SimParams params = preset_;
  // The studio runs past the preset's end on request; it stops itself at end_cycle_.
  params.stop.time.reset();
  params.stop.cycles = end_cycle_ + kMaxExtraCycles;
  return params;
}

void StudioSession::restart() {
  VoxelRock initial = buildInitialRock(shape_, preset_);
  initial_rock_ = initial.count(Material::Rock);
  end_cycle_ = plannedCycles(preset_, initial.layout.h);
  // Built before the old one goes: out of memory here, the session stays as it was.
  auto fresh = std::make_unique<WeatheringSimulation>(std::move(initial), simParams());
  SimulationSnapshot start = fresh->snapshot();
  sim_ = std::move(fresh);
  checkpoints_.restart(std::move(start), checkpointSpacing());
  history_.clear();
  ++rock_version_;
}

int StudioSession::checkpointSpacing() const {
  return std::max(1, end_cycle_ / kCheckpointsPerRun);
}

void StudioSession::restore(const SimulationSnapshot& checkpoint) {
  // The old simulation goes first: with memory short, its memory is what the new
  // one needs. Should building the new one fail, recover() tries again later.
  sim_.reset();
  lost_at_ = checkpoint.cycle;
  ++rock_version_;
  sim_ = std::make_unique<WeatheringSimulation>(SimulationSnapshot(checkpoint), simParams());
  lost_at_ = -1;
  history_.resize(std::size_t(sim_->cycle()));
}

void StudioSession::recover() {
  if (!sim_) restore(checkpoints_.atOrBefore(lost_at_));
}

const WeatheringSimulation& StudioSession::simulation() const {
  if (!sim_)
    throw StudioError(503,
                      "the simulation is being rebuilt after running out of memory; close other programs and "
                      "try again");
  return *sim_;
}

int StudioSession::cycle() const {
  return simulation().cycle();
}
double StudioSession::h() const {
  return simulation().rock().layout.h;
}
double StudioSession::time() const {
  return cycle() * h();
}
bool StudioSession::finished() const {
  return simulation().finished();
}
bool StudioSession::keepsOwnStop() const {
  return cycle() == end_cycle_;
}

bool StudioSession::atEnd() const {
  return cycle() >= end_cycle_ || finished();
}

CycleStats StudioSession::step() {
  recover();
  if (finished()) return {};
  const int from = cycle();
  try {
    const CycleStats stats = sim_->step();
    history_.push_back({stats.time, stats.rock, stats.exposed, stats.colluvium});
    ++rock_version_;
    if (checkpoints_.wants(stats.cycle)) checkpoints_.keep(sim_->snapshot());
    return stats;
  } catch (const std::bad_alloc&) {
    // A cycle cut short may have left the simulation half-done: back to the latest checkpoint
    // (or, should that fail too, to be rebuilt by recover()).
    try {
      restore(checkpoints_.atOrBefore(from));
    } catch (const std::bad_alloc&) {
    }
    throw StudioError(503, fmt::format("out of memory running the cycle after time {:.4g}: the studio went back to "
                                       "time {:.4g} and carries on from there; close other programs or restart the "
                                       "studio at a lower --resolution",
                                       from * h(), time()));
  }
}

void StudioSession::reset() {
  recover();
  restore(checkpoints_.atOrBefore(0));
  checkpoints_.restart(sim_->snapshot(), checkpointSpacing());
}

int StudioSession::cycleAt(double t) const {
  if (!std::isfinite(t) || t < 0) throw StudioError(400, "the time must be a number >= 0");
  const double cycles = std::ceil(t / h() - 1e-9);
  const int limit = end_cycle_ + kMaxExtraCycles;
  if (cycles > limit)
    throw StudioError(400, fmt::format("time {} is past what the studio runs ({} cycles of {:.4g}, time {:.4g})", t,
                                       limit, h(), limit * h()));
  return int(cycles);
}

void StudioSession::seek(double t) {
  recover();
  const int target = cycleAt(t);
  // The latest checkpoint at or before the target; restore it when it is ahead of
  // the simulation (a shortcut forward) or when the target lies behind it.
  const SimulationSnapshot& nearest = checkpoints_.atOrBefore(target);
  if (target < cycle() || nearest.cycle > cycle()) restore(nearest);
  while (cycle() < target && !finished()) step();
}

void StudioSession::runUntil(double t) {
  seek(t);
}

// The edit's keys as --set overrides of the preset file (the studio's API, docs/studio.md): the
// keyframed keys of the schema (schema::keyframedKeys) by their top-level name; a graph edit gives
// its points, and its noise or none.
std::vector<std::string> StudioSession::editOverrides(const json& part, PresetOverrides& overrides) const {
  const std::vector<std::string> editable = schema::keyframedKeys();
  std::vector<std::string> tops, under_durability;
  for (const auto& path : editable) {
    const std::string top = path.substr(0, path.find('.'));
    if (std::find(tops.begin(), tops.end(), top) == tops.end()) tops.push_back(top);
    if (path.rfind("durability.", 0) == 0) under_durability.push_back(path.substr(std::strlen("durability.")));
  }
  if (!part.is_object() || part.empty())
    throw StudioError(400, "an edit is a JSON object with any of " + joinNamesWith(tops, "and"));
  std::vector<std::string> paths;
  const auto set = [&](const std::string& key, const json& value) {
    overrides.sets.push_back(key + "=" + value.dump());
    overrides.set_origins.push_back("POST /api/edit " + key);
    paths.push_back(key);
  };
  for (const auto& [key, value] : part.items()) {
    if (key == "durability") {
      if (!value.is_object() || !value.contains("points"))
        throw StudioError(400, "durability: expected {\"points\": [[altitude, durability], ...], \"noise\": [...]}");
      for (const auto& [k, v] : value.items())
        if (std::find(under_durability.begin(), under_durability.end(), k) == under_durability.end())
          throw StudioError(400, "durability." + k + ": only the graph (" + joinNames(under_durability) +
                                     ") can be edited in the studio; edit the preset file for the rest");
      set("durability.points", value["points"]);
      set("durability.noise",
          value.value("noise", json::array()).is_null() ? json::array() : value.value("noise", json::array()));
    } else if (std::find(editable.begin(), editable.end(), key) != editable.end()) {
      set(key, value);
    } else {
      throw StudioError(400, "'" + key + "' cannot be edited in the studio: only " + joinNamesWith(tops, "and"));
    }
  }
  return paths;
}

void StudioSession::edit(const json& part) {
  recover();
  PresetOverrides overrides;
  overrides.resolution = resolution_;
  const std::vector<std::string> paths = editOverrides(part, overrides);
  Preset parsed;
  try {
    parsed = parsePreset(original_text_, file_, overrides);
  } catch (const InputError& e) {
    throw StudioError(400, e.what());
  }
  Preset candidate = preset_;
  applyKeyframeEdit(candidate, keyframeEditOf(parsed, paths), time(), h());
  if (cycle() == 0) {  // the preset itself changed: the run starts again
    std::swap(preset_, candidate);
    try {
      restart();
    } catch (...) {
      std::swap(preset_, candidate);  // the edit did not happen
      throw;
    }
    return;
  }
  const GridLayout now = sim_->rock().layout, then = computeGridLayout(candidate);
  if (then.margin != now.margin) {
    const double largest = (now.margin - 1) * now.h;
    throw StudioError(400, fmt::format("bubbles: a bubble that large needs an air margin of {} voxels and this grid "
                                       "has {} (the largest radius allowed now is about {:.4g}); put the larger "
                                       "bubble in the preset's bubbles and restart the studio",
                                       then.margin, now.margin, largest));
  }
  preset_ = std::move(candidate);
  sim_->setKeyframes(preset_.durability.keyframes);
  checkpoints_.dropAfter(cycle());
}

json StudioSession::state() const {
  const double t = time();
  // What is in effect now: the base graph, then every keyframe reached (one at
  // the current time included: the next cycle runs with it).
  DurabilityGraph graph = preset_.durability.graph;
  std::vector<BubbleBand> bubbles = preset_.bubbles;
  ResponseParams response = preset_.response;
  for (const auto& k : preset_.durability.keyframes) {
    if (k.at > t && !sameKeyframeTime(k.at, t, h())) break;
    if (k.graph) graph = *k.graph;
    if (k.bubbles) bubbles = *k.bubbles;
    if (k.response) response = *k.response;
  }
  Preset active_preset = preset_;
  active_preset.bubbles = bubbles;
  active_preset.response = response;
  const json active_json = presetToJson(active_preset);
  // f sampled for the page's response graph: the page draws it, never evaluates it.
  json response_curve = json::array();
  for (int i = 0; i <= kResponseSamples; ++i)
    response_curve.push_back({double(i) / kResponseSamples, applyResponse(response, double(i) / kResponseSamples)});
  json history = json::array();
  for (const auto& e : history_) history.push_back({e.time, e.rock});
  json checkpoints = json::array();
  for (const int c : checkpoints_.cycles()) checkpoints.push_back(c * h());
  const GridLayout& g = simulation().rock().layout;
  const SimulationCounts counts = simulation().counts();
  return {{"cycle", cycle()},
          {"time", t},
          {"h", h()},
          {"end_time", end_cycle_ * h()},
          {"planned_cycles", end_cycle_},
          {"finished", finished() || cycle() >= end_cycle_ + kMaxExtraCycles},
          {"at_end", atEnd()},
          {"rock", counts.rock},
          {"initial_rock", initial_rock_},
          {"exposed", counts.exposed},
          {"colluvium", counts.colluvium},
          {"resolution", resolution_},
          {"grid", {{"nx", g.nx}, {"ny", g.ny}, {"nz", g.nz}, {"h", g.h}, {"margin", g.margin}}},
          {"history", history},
          {"checkpoints", checkpoints},
          {"checkpoint_bytes", checkpoints_.bytes()},
          {"mesh_version", rock_version_},
          {"preset", presetToJson(preset_)},
          {"active",
           {{"durability", graphJson(preset_, graph)},
            {"bubbles", active_json["bubbles"]},
            {"response", active_json["response"]}}},
          {"response_curve", response_curve}};
}

void StudioSession::requireMemoryFor(const std::string& what) const {
  const std::uint64_t needed = estimatePreviewBytes(simulation().rock().layout), free = memoryHeadroomBytes();
  if (free < needed)
    throw StudioError(503, fmt::format("not enough memory for {}: it needs about {} MiB and this process can take {} "
                                       "MiB more; close other programs, or restart the studio at a lower --resolution",
                                       what, needed >> 20, free >> 20));
}

std::string StudioSession::rockVdb() const {
  requireMemoryFor("rock.vdb");
  std::ostringstream out;
  writeRockVdb(simulation().rock(), out);
  return std::move(out).str();
}

std::string StudioSession::previewMesh(Palette palette) const {
  requireMemoryFor("the preview mesh");
  const AssetMeshes meshes = previewMeshes(simulation().rock(), preset_, simulation().activeParams(), palette);
  std::string out = "RBPM";
  appendU32(out, 1);
  appendU32(out, std::uint32_t(cycle()));
  appendMesh(out, meshes.rock);
  appendMesh(out, meshes.colluvium);
  return out;
}

std::string StudioSession::savedYaml(const std::string& name) const {
  YAML::Node root = YAML::Load(original_text_);
  const json resolved = presetToJson(preset_);
  root["name"] = name;
  if (!root["durability"].IsMap()) root["durability"] = YAML::Node(YAML::NodeType::Map);
  YAML::Node durability = root["durability"];
  const json graph = graphJson(preset_, preset_.durability.graph);
  durability["points"] = toYaml(graph["points"]);
  if (graph.contains("noise"))
    durability["noise"] = toYaml(graph["noise"]);
  else
    durability.remove("noise");
  durability["keyframes"] = toYaml(resolved["durability"]["keyframes"]);
  root["bubbles"] = toYaml(resolved["bubbles"]);
  root["response"] = toYaml(resolved["response"]);
  // Run to the preset's own end, the preset's `time` (or `cycles`) stays as written: the
  // current time is that end snapped to preview cycles, and written out it would make the final
  // bake at the preset's resolution run a cycle more than the preset asks. Stopped anywhere
  // else, the current time is the artist's choice.
  if (!keepsOwnStop()) {
    root.remove("cycles");
    root["time"] = YAML::Node(fmt::format("{}", time()));
  }
  YAML::Emitter out;
  out << root;
  return std::string("# Saved by rockbake studio at time ") + fmt::format("{}", time()) + " (resolution " +
         std::to_string(resolution_) + ") from " + file_.filename().string() + "\n" + out.c_str() + "\n";
}

Preset StudioSession::finalPreset() const {
  if (cycle() == 0) throw StudioError(409, "run at least one cycle first: the final bake bakes the current time");
  return parsePreset(savedYaml(preset_.name), file_);
}

SaveResult StudioSession::save(const std::string& name, bool overwrite) {
  // Not starting with '-': `rockbake lint *.yaml` would read a file named -x.yaml as an option.
  static const std::regex kName("[a-z0-9_][a-z0-9_-]{0,63}");
  if (!std::regex_match(name, kName))
    throw StudioError(400,
                      "name: '" + name + "' is not a save name: use 1 to 64 of a-z, 0-9, _ and -, not starting with -");
  if (cycle() == 0)
    throw StudioError(409, "run at least one cycle before saving: a saved preset bakes at least one cycle");
  const fs::path folder = file_.parent_path();
  const fs::path target = folder / (name + ".yaml");
  std::error_code ec;
  for (const auto& source : preset_.sources)
    if (fs::equivalent(source, target, ec))
      throw StudioError(409, target.string() + " is the studio's preset or a file it extends; choose another name");
  if (fs::exists(target) && !overwrite)
    throw StudioError(409, target.string() + " exists; choose another name or save with overwrite");

  // Validate before it is put in place: read back at the studio's resolution,
  // it must be exactly the studio's preset (name and time aside).
  const std::string text = savedYaml(name);
  const fs::path scratch = folder / ("." + name + ".studio-check.yaml");
  Preset expected = preset_;
  expected.name = name;
  if (!keepsOwnStop()) {
    expected.stop.time = time();
    expected.stop.cycles.reset();
  }
  try {
    writeFileAtomically(scratch, text);
    const Preset reread = loadPreset(scratch, {{}, std::nullopt, resolution_});
    fs::remove(scratch, ec);
    if (presetToJson(reread) != presetToJson(expected))
      throw StudioError(500, "the saved preset does not read back as the studio's; nothing was saved");
  } catch (const InputError& e) {
    fs::remove(scratch, ec);
    throw StudioError(500, std::string("the saved preset does not validate (nothing was saved): ") + e.what());
  }
  writeFileAtomically(target, text);
  return {target, time(), presetFingerprint(expected, {})};
}

}  // namespace rockbake
