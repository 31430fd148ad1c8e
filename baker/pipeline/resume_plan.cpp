#include "pipeline/resume_plan.h"

#include <algorithm>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "pipeline/manifest.h"
#include "preset/keyframe_edit.h"
#include "preset/preset_json.h"
#include "preset/schema.h"
#include "preset/yaml_text.h"

namespace rockbake {
namespace {

// The key path a "--set key.path=VALUE" names.
std::string setPath(const std::string& set) {
  return set.substr(0, set.find('='));
}

// Whether `path` is one of `prefixes` or lies under one.
bool underAny(const std::string& path, const std::vector<std::string>& prefixes) {
  return std::any_of(prefixes.begin(), prefixes.end(),
                     [&](const std::string& prefix) { return path == prefix || path.rfind(prefix + ".", 0) == 0; });
}

// `sets` split into the keyframed ones and those that apply from the checkpoint on; anything else is refused.
void sortSets(const std::vector<std::string>& sets, std::vector<std::string>& keyframed,
              std::vector<std::string>& direct) {
  const std::vector<std::string> keyframed_keys = schema::keyframedKeys(), direct_keys = schema::resumableKeys();
  for (const auto& set : sets) {
    const std::string path = setPath(set);
    if (!path.empty() && underAny(path, keyframed_keys))
      keyframed.push_back(set);
    else if (!path.empty() && underAny(path, direct_keys))
      direct.push_back(set);
    else {
      std::vector<std::string> allowed = keyframed_keys;
      allowed.insert(allowed.end(), direct_keys.begin(), direct_keys.end());
      throw InputError(
          {"--set " + set}, path,
          "a resumed bake cannot change '" + path + "': the checkpoint's state was made with it",
          "resume may change " + joinNamesWith(allowed, "and") + "; bake from the start to change the rest");
    }
  }
}

}  // namespace

ResumePlan planResume(const Checkpoint& c, const std::vector<std::string>& sets) {
  std::vector<std::string> keyframed, direct;
  sortSets(sets, keyframed, direct);

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

  ResumePlan plan;
  plan.overrides = c.overrides;
  plan.overrides.set_origins.resize(plan.overrides.sets.size());
  for (const auto& set : direct) plan.overrides.sets.push_back(set), plan.overrides.set_origins.push_back("");
  // Edits of the graph, bubbles and response become a keyframe at the checkpoint's time, as in the studio.
  std::vector<std::string> keyframed_paths;
  for (const auto& set : keyframed) keyframed_paths.push_back(setPath(set));
  const KeyframeEdit edit = keyframeEditOf(edited, keyframed_paths);
  if (!edit.empty()) {
    if (c.snapshot.cycle == 0)
      throw InputError({"--set " + keyframed.front()}, keyframed_paths.front(),
                       "the checkpoint is at time 0, where an edit changes the preset itself",
                       "bake the preset from the start with these --set");
    const double h = c.snapshot.rock.layout.h;
    const double t = c.snapshot.cycle * h;
    Preset with = original;
    const std::vector<double> dropped = applyKeyframeEdit(with, edit, t, h);
    if (!dropped.empty())
      spdlog::warn(
          "resume: the edit at time {} drops the preset's later keyframes (at {}): they belong to the run "
          "the checkpoint leaves",
          t, fmt::join(dropped, ", "));
    plan.overrides.sets.push_back("durability.keyframes=" + presetToJson(with)["durability"]["keyframes"].dump());
    plan.overrides.set_origins.push_back("");
  }
  plan.preset = parsePreset(c.preset_text, c.preset_file, plan.overrides);
  return plan;
}

}  // namespace rockbake
