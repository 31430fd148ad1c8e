// The preset schema as data (docs/preset-reference.md): what every key is,
// read from the one table in preset/schema.cpp. The reader and validation
// (preset/read_preset.h), the JSON writer (preset/preset_json.h), `extends`
// merging, the keys the studio and `rockbake resume` may edit, the enum names
// and docs/preset-reference.md all come from that table.
//
// This header is the table's public face, for any stage: enum names, the keys
// by path, and who may edit them. It throws nothing.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "preset/preset.h"

namespace rockbake::schema {

// ---- enum names: the one place each enum's YAML/JSON name is written ----

template <class E>
struct EnumName {
  E value;
  const char* name;
};
// Every value of E with its name, in the reference's order. Defined for Palette,
// RockfallMode, ImageMode, BubbleSpec::Kind, ResponseParams::Kind, HullNaming, DeliveryProfile,
// TextureMap, LodMapSize and MapPrecision.
template <class E>
std::span<const EnumName<E>> enumNames();

template <class E>
const char* nameOf(E value) {
  for (const auto& n : enumNames<E>())
    if (n.value == value) return n.name;
  return "";
}
template <class E>
std::optional<E> valueNamed(std::string_view name) {
  for (const auto& n : enumNames<E>())
    if (name == n.name) return n.value;
  return std::nullopt;
}
template <class E>
std::vector<std::string> namesOf() {
  std::vector<std::string> names;
  for (const auto& n : enumNames<E>()) names.emplace_back(n.name);
  return names;
}

// ---- who may edit a key once a run has started ----

// The parts a keyframe carries (DurabilityKeyframe): an edit of a key marked
// with one becomes (part of) a keyframe.
enum class KeyframePart { Graph, Bubbles, Response };

// Key paths through maps only (a key inside a list is edited with its list).
// The keys the studio edits and `resume` records as a keyframe at the checkpoint's time:
// durability.points, durability.noise, bubbles, response.
std::vector<std::string> keyframedKeys();
// The keys `resume` may change from the checkpoint on: rockfall, colluvium, time, cycles, until.
std::vector<std::string> resumableKeys();
// The keyframe part `key_path` (or a key above it) edits, if it is a keyframed key or lies under one.
std::optional<KeyframePart> keyframePartOf(const std::string& key_path);

// ---- extends ----

// A key a preset gives that replaces more of its base than itself: when the
// preset gives any of `when_given` in the map at `path`, the base's `drops`
// there are not inherited. From the table: each set of alternatives (`time` or
// `cycles`, a shape's kind, a response's kind) drops the base's choice; a key
// sized by another (durability.noise, one entry per segment of points) goes
// with it.
struct MergeRule {
  std::string path;
  std::vector<std::string> when_given;
  std::vector<std::string> drops;
};
const std::vector<MergeRule>& mergeRules();

// The keys beside `key_path` that setting it on the command line removes: the
// other choices of an exactly-one set (`--set cycles=40` removes `time`). A
// kind (`shape.sphere`) removes nothing: the map then has two kinds, which the
// reader refuses by name.
std::vector<std::string> siblingsReplacedBy(const std::string& key_path);

// ---- the reference ----

// The generated part of docs/preset-reference.md: every key with its value,
// unit, default, who may edit it and its one-line description, map by map.
std::string presetReferenceTables();

}  // namespace rockbake::schema
