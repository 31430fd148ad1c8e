#include "preset/keyframe_edit.h"

#include <algorithm>
#include <cmath>

#include "preset/schema.h"

namespace rockbake {

KeyframeEdit keyframeEditOf(const Preset& edited, const std::vector<std::string>& key_paths) {
  KeyframeEdit edit;
  for (const auto& path : key_paths) {
    const std::optional<schema::KeyframePart> part = schema::keyframePartOf(path);
    if (part == schema::KeyframePart::Graph) edit.graph = edited.durability.graph;
    if (part == schema::KeyframePart::Bubbles) edit.bubbles = edited.bubbles;
    if (part == schema::KeyframePart::Response) edit.response = edited.response;
  }
  return edit;
}

bool sameKeyframeTime(double a, double b, double h) {
  return std::abs(a - b) <= 1e-9 * h;
}

std::vector<double> applyKeyframeEdit(Preset& preset, const KeyframeEdit& edit, double t, double h) {
  auto& keyframes = preset.durability.keyframes;
  std::vector<double> dropped;
  std::erase_if(keyframes, [&](const DurabilityKeyframe& k) {
    const bool later = k.at > t && !sameKeyframeTime(k.at, t, h);
    if (later) dropped.push_back(k.at);
    return later;
  });
  if (sameKeyframeTime(t, 0.0, h)) {
    if (edit.graph) preset.durability.graph = *edit.graph;
    if (edit.bubbles) preset.bubbles = *edit.bubbles;
    if (edit.response) preset.response = *edit.response;
    for (auto& k : keyframes) {
      if (edit.graph) k.graph.reset();
      if (edit.bubbles) k.bubbles.reset();
      if (edit.response) k.response.reset();
    }
    std::erase_if(keyframes, [](const DurabilityKeyframe& k) { return !k.graph && !k.bubbles && !k.response; });
    return dropped;
  }
  if (keyframes.empty() || !sameKeyframeTime(keyframes.back().at, t, h)) keyframes.emplace_back();
  DurabilityKeyframe& k = keyframes.back();
  k.at = t;
  if (edit.graph) k.graph = *edit.graph;
  if (edit.bubbles) k.bubbles = *edit.bubbles;
  if (edit.response) k.response = *edit.response;
  return dropped;
}

}  // namespace rockbake
