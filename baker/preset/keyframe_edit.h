// One edit during a run, "these parts from time t on" (docs/studio.md,
// docs/libraries.md): the studio's edits and `rockbake resume --set` both
// become keyframes through applyKeyframeEdit, with one rule for matching times
// and one for the keyframes after the edit.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "preset/preset.h"

namespace rockbake {

// New values for any of a keyframe's parts (DurabilityKeyframe): the
// durability graph (points and noise), the bubble graph, the response.
struct KeyframeEdit {
  std::optional<DurabilityGraph> graph;
  std::optional<std::vector<BubbleBand>> bubbles;
  std::optional<ResponseParams> response;
  bool empty() const { return !graph && !bubbles && !response; }
};

// The parts that `key_paths` name (keys the schema marks as keyframed, or keys
// under them: "durability.points", "bubbles.0.up_to"; others are ignored),
// each with the value `edited` gives it, whole.
KeyframeEdit keyframeEditOf(const Preset& edited, const std::vector<std::string>& key_paths);

// Two keyframe times are the same when they are within a billionth of a cycle
// (h, the voxel size, is a cycle's length of time): the tolerance the
// simulation reaches keyframes with (sim/weathering.cpp), so a time written
// as a decimal (at: 0.3) is the cycle it falls on (6 × 0.05 in binary).
bool sameKeyframeTime(double a, double b, double h);

// Applies `edit` to `preset` from time `t` on (h: the cycle's length):
// - At time 0 it edits the preset itself (durability graph, bubbles,
//   response); keyframes at time 0 lose the parts edited (they would replace
//   the edit at once) and are dropped when nothing is left in them.
// - Later, the parts go into a keyframe at t: merged into one already there
//   (which then takes t exactly), else a new one.
// Either way every keyframe after t is dropped: an edit at t starts a new
// branch of the run, and the keyframes ahead belonged to the run it leaves
// (the studio after seeking back; `resume` from a checkpoint at t).
// Returns the times of the keyframes dropped.
std::vector<double> applyKeyframeEdit(Preset& preset, const KeyframeEdit& edit, double t, double h);

}  // namespace rockbake
