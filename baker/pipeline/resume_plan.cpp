#include "pipeline/resume_plan.h"

#include <algorithm>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "pipeline/manifest.h"
#include "preset/preset_json.h"

namespace rockbake {

ResumePlan planResume(const Checkpoint& c, const std::vector<std::string>& sets) {
  static const std::vector<std::string> kKeyframed = {"durability.points", "durability.noise", "bubbles", "response"};
  static const std::vector<std::string> kDirect = {"colluvium", "rockfall", "time", "cycles", "until"};
  const auto under = [](const std::string& path, const std::string& prefix) {
    return path == prefix || path.rfind(prefix + ".", 0) == 0;
  };
  std::vector<std::string> keyframed, direct;
  for (const auto& set : sets) {
    const std::string path = set.substr(0, set.find('='));
    const auto matches = [&](const std::vector<std::string>& prefixes) {
      return std::any_of(prefixes.begin(), prefixes.end(), [&](const std::string& p) { return under(path, p); });
    };
    if (matches(kKeyframed))
      keyframed.push_back(set);
    else if (matches(kDirect))
      direct.push_back(set);
    else
      throw InputError({"--set " + set}, path,
                       "a resumed bake cannot change '" + path + "': the checkpoint's state was made with it",
                       "resume may change durability.points, durability.noise, bubbles, response, colluvium, "
                       "rockfall, time, cycles and until; bake from the start to change the rest");
  }

  const Preset original = parsePreset(c.preset_text, c.preset_file, c.overrides);
  if (presetFingerprint(original, {}) != c.preset_hash)
    throw InputError({c.preset_file.string()}, "",
                     "the preset reads differently now than when the checkpoint was written (a file it extends or "
                     "a shape changed?)",
                     "restore it, or bake from the start");
  PresetOverrides edited_overrides = c.overrides;
  for (const auto& set : sets) edited_overrides.sets.push_back(set), edited_overrides.set_origins.push_back("");
  edited_overrides.set_origins.resize(edited_overrides.sets.size());
  const Preset edited = parsePreset(c.preset_text, c.preset_file, edited_overrides);  // validates the edits

  // Changes to the graph, bubbles and response become a keyframe at the checkpoint's time.
  const double h = c.snapshot.rock.layout.h;
  const double t = c.snapshot.cycle * h;
  std::vector<DurabilityKeyframe> keyframes = original.durability.keyframes;
  DurabilityKeyframe k;
  k.at = t;
  const nlohmann::json before = presetToJson(original), after = presetToJson(edited);
  if (before["durability"]["points"] != after["durability"]["points"] ||
      before["durability"]["noise"] != after["durability"]["noise"])
    k.graph = edited.durability.graph;
  if (before["bubbles"] != after["bubbles"]) k.bubbles = edited.bubbles;
  if (before["response"] != after["response"]) k.response = edited.response;

  ResumePlan plan;
  plan.overrides = c.overrides;
  plan.overrides.set_origins.resize(plan.overrides.sets.size());
  for (const auto& set : direct) plan.overrides.sets.push_back(set), plan.overrides.set_origins.push_back("");
  if (k.graph || k.bubbles || k.response) {
    auto at = std::find_if(keyframes.begin(), keyframes.end(), [&](const DurabilityKeyframe& e) { return e.at >= t; });
    if (at != keyframes.end() && at->at == t) {  // one already at that time: the edit merges into it
      if (k.graph) at->graph = k.graph;
      if (k.bubbles) at->bubbles = k.bubbles;
      if (k.response) at->response = k.response;
    } else {
      keyframes.insert(at, k);
    }
    Preset with = original;
    with.durability.keyframes = keyframes;
    plan.overrides.sets.push_back("durability.keyframes=" + presetToJson(with)["durability"]["keyframes"].dump());
    plan.overrides.set_origins.push_back("");
  }
  plan.preset = parsePreset(c.preset_text, c.preset_file, plan.overrides);
  return plan;
}

}  // namespace rockbake
