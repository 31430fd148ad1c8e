// The machinery the preset schema's table (preset/schema.cpp) is written in,
// and the reading and writing that walk it (docs/preset-reference.md).
// Internal to the preset stage: it exposes yaml-cpp through preset/yaml_field.h.
//
// A MapSpec<S> lists, in reading order, the keys of a YAML map that fills a
// struct S. A Key<S> is one key: the member it fills (an accessor), its
// Value<T> (preset/schema_values.h: how YAML becomes the member's type T and
// T becomes JSON, and what the reference says of it), whether it must be
// given, the named checks run before and after it is read (rules a table
// cannot express, preset/schema_rules.h), its unit and one-line doc, and who
// may edit it once a run has started. A map may hold
// one set of kinds (the map is exactly one of them: a shape, a bubble, a
// response) and sets of exactly-one alternatives (`time` or `cycles`).
//
// Reading goes through Field (preset/yaml_field.h), so every problem names
// file:line:column and key path, and the keys each read asks for are the
// ones reportUnreadKeys() knows. Keys are asked for in table order; a map
// with kinds asks for its other keys first, so that one misspelt among them is
// recognised even when the kind is missing.
#pragma once

#include <algorithm>
#include <functional>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include <nlohmann/json.hpp>

#include "preset/preset.h"
#include "preset/schema.h"
#include "preset/yaml_field.h"

namespace rockbake::schema {

using nlohmann::json;

// What a read knows besides its own value.
struct ReadContext {
  const Preset& preset;  // the keys read so far: `grid` is read before anything that needs the voxel size
  const Source& source;  // its problems list is set: parts of a preset record their problems there
  double h() const {
    const Vec3d& size = preset.grid.size;
    return std::max({size[0], size[1], size[2]}) / preset.grid.resolution;
  }
};

// Runs one part of the reading: a problem is recorded (with where its reading stopped) and the next part
// goes on, so that one run lists every problem (`rockbake lint`); loading then reports the first.
template <class Read>
bool readPart(const Source& source, Read&& read) {
  try {
    read();
    return true;
  } catch (const InputError& e) {
    source.reads->failed.push_back(e.keyPath());
    source.problems->push_back(e);
    return false;
  }
}

struct MapInfo;
using MapInfoOf = const MapInfo& (*)();

// How a key's YAML becomes a T (into a T that holds its default, or what was read before it), how T
// becomes JSON, and what the reference says about it.
template <class T>
struct Value {
  std::string type;         // the reference's type: "number", "3 lengths", "list"
  std::string range;        // and range: "[0, 1]", "> 0", "8 … 2048"
  MapInfoOf map = nullptr;  // a map's keys, or each item's for a list of maps
  bool list = false;        // with `map`: a list of such maps
  std::function<void(const Field&, T&, const ReadContext&)> read;
  std::function<json(const T&)> write;
};

enum class Presence {
  Optional,       // absent or null: the member keeps its default
  Required,       // Field::require: a problem at the key when it is given empty, else at the map
  RequiredHere,   // a problem at the map when it is absent or null
  ValueRequired,  // always read: the value's own problem ("expected a number, found nothing")
};
enum class Emit {
  Always,          // absent optionals are left out
  NullWhenAbsent,  // an absent optional is written as null
  WhenNotEmpty,    // an empty list or map is left out
};

// What the reference, `extends` and the edit lists know of a key (type-erased).
struct KeyInfo;
template <class T>
KeyInfo keyInfo(std::string name, std::string doc, const Value<T>& value);
struct KeyInfo {
  std::string name;  // empty for keys written inline (the durability graph's points and noise)
  std::string doc;
  std::string unit;
  std::string type, range;  // Value::type and ::range, or what .range() gives
  MapInfoOf map = nullptr;  // its map's keys (inline: keys of this same map)
  bool list = false;
  bool kind = false;  // one of its map's kinds
  Presence presence = Presence::Optional;
  std::string missing, missing_hint;  // the problem when a required key is absent
  Emit emit = Emit::Always;
  std::optional<KeyframePart> keyframe;  // the studio and `resume` edit it as (part of) a keyframe
  bool resume = false;                   // `resume` may change it from the checkpoint on
  std::string inherited_with;            // from a base, inherited only with this sibling (noise: points)
  std::string default_text;              // what the reference says the default is, when the struct's own cannot say it
  std::string see;                       // the key whose map this one's is, documented there instead ("bubbles")
  std::function<std::optional<json>()> default_json;  // the member of a default-constructed struct
};
template <class T>
KeyInfo keyInfo(std::string name, std::string doc, const Value<T>& value) {
  KeyInfo info;
  info.name = std::move(name), info.doc = std::move(doc);
  info.type = value.type, info.range = value.range, info.map = value.map, info.list = value.list;
  return info;
}

// A set of keys of which exactly one is given. Kinds (`kind`) are what the map is: read first,
// with Field::oneOf's messages; other sets are read at the place of their first key, with these.
struct Alternatives {
  std::vector<std::string> names;
  bool kind = false;
  std::string missing, both, hint;
  bool has(const std::string& name) const { return std::find(names.begin(), names.end(), name) != names.end(); }
};
inline Alternatives kinds(std::vector<std::string> names) {
  Alternatives group;
  group.names = std::move(names);
  group.kind = true;
  return group;
}
inline Alternatives exactlyOne(std::vector<std::string> names, std::string missing, std::string both,
                               std::string hint) {
  Alternatives group;
  group.names = std::move(names);
  group.missing = std::move(missing), group.both = std::move(both), group.hint = std::move(hint);
  return group;
}

struct MapInfo {
  std::vector<KeyInfo> keys;
  std::vector<Alternatives> alternatives;
  std::string note;  // what the reference adds below the map's keys (rules between them)
};

template <class S>
using Check = void (*)(const Field& map, const S& value, std::type_identity_t<const S*> previous,
                       const ReadContext& ctx);

template <class S>
struct Key {
  KeyInfo info;
  std::function<void(const Field& value, S&, const ReadContext&)> assign;  // inline keys: the map itself
  std::function<std::optional<json>(const S&)> to_json;                    // nothing: an absent optional
  std::function<void(const S&, json& map)> write_inline;                   // inline keys only
  std::function<bool(const S&)> holds;                                     // kinds only: the kind `S` holds
  std::function<void(S&, const ReadContext&)> when_absent;
  std::vector<Check<S>> before, after;  // run with the key known to be given, before and after reading it

  Key&& unit(std::string u) && { return info.unit = std::move(u), std::move(*this); }
  Key&& required(std::string problem, std::string hint = {}) && {
    info.presence = Presence::Required, info.missing = std::move(problem), info.missing_hint = std::move(hint);
    return std::move(*this);
  }
  Key&& requiredHere(std::string problem) && {
    return info.presence = Presence::RequiredHere, info.missing = std::move(problem), std::move(*this);
  }
  Key&& always() && { return info.presence = Presence::ValueRequired, std::move(*this); }
  Key&& checkFirst(Check<S> check) && { return before.push_back(check), std::move(*this); }
  Key&& check(Check<S> check) && { return after.push_back(check), std::move(*this); }
  Key&& nullWhenAbsent() && { return info.emit = Emit::NullWhenAbsent, std::move(*this); }
  Key&& leftOutWhenEmpty() && { return info.emit = Emit::WhenNotEmpty, std::move(*this); }
  Key&& keyframed(KeyframePart part) && { return info.keyframe = part, std::move(*this); }
  Key&& resumable() && { return info.resume = true, std::move(*this); }
  Key&& inheritedWith(std::string sibling) && { return info.inherited_with = std::move(sibling), std::move(*this); }
  Key&& byDefault(std::function<void(S&, const ReadContext&)> fill, std::string text) && {
    when_absent = std::move(fill), info.default_text = std::move(text);
    return std::move(*this);
  }
  // What the reference says, where the table's own value cannot say it.
  Key&& range(std::string r) && { return info.range = std::move(r), std::move(*this); }
  Key&& defaultIs(std::string text) && { return info.default_text = std::move(text), std::move(*this); }
  Key&& see(std::string key_path) && { return info.see = std::move(key_path), std::move(*this); }
};

template <class S>
struct MapSpec {
  using Struct = S;
  MapInfo info;
  std::vector<Key<S>> keys;
  bool keys_apart = false;  // the preset's top level: a problem in one key does not stop the others

  MapSpec(std::vector<Key<S>> k, std::vector<Alternatives> alternatives = {}, std::string note = {}, bool apart = false)
      : keys(std::move(k)), keys_apart(apart) {
    for (const auto& key : keys) info.keys.push_back(key.info);
    info.alternatives = std::move(alternatives);
    info.note = std::move(note);
  }
  MapSpec(const MapSpec&) = delete;

  const Key<S>& key(const std::string& name) const {
    return *std::find_if(keys.begin(), keys.end(), [&](const Key<S>& k) { return k.info.name == name; });
  }
  const Alternatives* groupOf(const std::string& name) const {
    for (const auto& group : info.alternatives)
      if (group.has(name)) return &group;
    return nullptr;
  }
  const Alternatives* kinds() const {
    for (const auto& group : info.alternatives)
      if (group.kind) return &group;
    return nullptr;
  }
};

// ---- reading ----

template <class S>
void readKeys(const MapSpec<S>& spec, const Field& map, S& s, std::type_identity_t<const S*> previous,
              const ReadContext& ctx);

template <class S>
void readMap(const MapSpec<S>& spec, const Field& map, S& s, std::type_identity_t<const S*> previous,
             const ReadContext& ctx) {
  if (spec.keys_apart)
    readPart(ctx.source, [&] { map.expectMap(); });
  else
    map.expectMap();
  readKeys(spec, map, s, previous, ctx);
}

template <class S>
void readKey(const Key<S>& key, const Field& map, S& s, std::type_identity_t<const S*> previous,
             const ReadContext& ctx) {
  const KeyInfo& k = key.info;
  if (k.name.empty()) return key.assign(map, s, ctx);
  if (k.presence == Presence::Optional && !map.has(k.name)) {
    if (key.when_absent) key.when_absent(s, ctx);
    return;
  }
  if (k.presence == Presence::Required) map.require(k.name, k.missing, k.missing_hint);
  if (k.presence == Presence::RequiredHere && !map.has(k.name)) map.fail(k.missing, k.missing_hint);
  for (const Check<S> check : key.before) check(map, s, previous, ctx);
  key.assign(map.at(k.name), s, ctx);
  for (const Check<S> check : key.after) check(map, s, previous, ctx);
}

template <class S>
void readAlternatives(const MapSpec<S>& spec, const Alternatives& group, const Field& map, S& s,
                      std::type_identity_t<const S*> previous, const ReadContext& ctx) {
  std::size_t given = 0;
  for (const auto& name : group.names) given += map.has(name) ? 1 : 0;
  if (given != 1) map.fail(given == 0 ? group.missing : group.both, group.hint);
  for (const auto& name : group.names) readKey(spec.key(name), map, s, previous, ctx);
}

template <class S>
void readKeys(const MapSpec<S>& spec, const Field& map, S& s, std::type_identity_t<const S*> previous,
              const ReadContext& ctx) {
  const auto step = [&](auto&& read) {
    if (spec.keys_apart)
      readPart(ctx.source, read);
    else
      read();
  };
  if (const Alternatives* kinds = spec.kinds()) {
    for (const auto& key : spec.keys)
      if (!key.info.name.empty() && !kinds->has(key.info.name)) map.has(key.info.name);
    step([&] { readKey(spec.key(map.oneOf(kinds->names)), map, s, previous, ctx); });
  }
  for (const auto& key : spec.keys) {
    const Alternatives* group = spec.groupOf(key.info.name);
    if (!group)
      step([&] { readKey(key, map, s, previous, ctx); });
    else if (!group->kind && group->names.front() == key.info.name)
      step([&] { readAlternatives(spec, *group, map, s, previous, ctx); });
  }
}

// ---- writing ----

template <class S>
void writeKeys(const MapSpec<S>& spec, const S& s, json& out) {
  for (const auto& key : spec.keys) {
    if (key.info.kind && !key.holds(s)) continue;
    if (key.write_inline) {
      key.write_inline(s, out);
      continue;
    }
    std::optional<json> value = key.to_json(s);
    if (!value) {
      if (key.info.emit == Emit::NullWhenAbsent) out[key.info.name] = nullptr;
      continue;
    }
    if (key.info.emit == Emit::WhenNotEmpty && value->empty()) continue;
    out[key.info.name] = std::move(*value);
  }
}

template <class S>
json writeMap(const MapSpec<S>& spec, const S& s) {
  json out = json::object();
  writeKeys(spec, s, out);
  return out;
}

// ---- keys ----

template <class T>
struct IsOptional : std::false_type {};
template <class T>
struct IsOptional<std::optional<T>> : std::true_type {};

// The accessor of a key whose map fills the struct it sits in (render.turntable, durability.strata.warp).
inline constexpr auto self = [](auto& s) -> auto& {
  return s;
};

// Makes the keys of maps that fill an S: k("yield", &ColluviumParams::yield, numberIn(0, 1), "...").
template <class S>
struct Keys {
  // A key filling `access(s)`: a T, or an optional<T> (set when the key is given).
  template <class Access, class T>
  Key<S> operator()(std::string name, Access access, Value<T> value, std::string doc) const {
    using Member = std::remove_cvref_t<std::invoke_result_t<Access, S&>>;
    Key<S> key;
    key.info = keyInfo(std::move(name), std::move(doc), value);
    if constexpr (IsOptional<Member>::value) {
      key.assign = [access, read = value.read](const Field& f, S& s, const ReadContext& ctx) {
        T v{};
        read(f, v, ctx);
        std::invoke(access, s) = std::move(v);
      };
      key.to_json = [access, write = value.write](const S& s) -> std::optional<json> {
        const auto& member = std::invoke(access, s);
        return member ? std::optional<json>(write(*member)) : std::nullopt;
      };
    } else {
      key.assign = [access, read = value.read](const Field& f, S& s, const ReadContext& ctx) {
        read(f, std::invoke(access, s), ctx);
      };
      key.to_json = [access, write = value.write](const S& s) -> std::optional<json> {
        return write(std::invoke(access, s));
      };
    }
    key.info.default_json = [to_json = key.to_json] { return to_json(S{}); };
    return key;
  }

  // A key with no member: `read` checks it (and refuses it); it is never written.
  Key<S> refused(std::string name, std::string type, void (*read)(const Field&), std::string doc) const {
    Key<S> key;
    key.info.name = std::move(name), key.info.doc = std::move(doc), key.info.type = std::move(type);
    key.assign = [read](const Field& f, S&, const ReadContext&) { read(f); };
    key.to_json = [](const S&) -> std::optional<json> { return std::nullopt; };
    return key;
  }

  // One of the map's kinds when S says its kind in an enum member `kind`: choosing it sets the
  // kind, then reads the value into `access(s)`. The key is the enum value's name.
  template <class E, class Access, class T>
  Key<S> kind(E which, Access access, Value<T> value, std::string doc) const {
    Key<S> key = (*this)(nameOf(which), access, std::move(value), std::move(doc)).always();
    key.info.kind = true;
    key.holds = [which](const S& s) { return s.kind == which; };
    key.assign = [which, assign = key.assign](const Field& f, S& s, const ReadContext& ctx) {
      s.kind = which;
      assign(f, s, ctx);
    };
    return key;
  }

  // One of the map's kinds when S holds them in a variant `access(s)`: choosing it reads a V whole.
  template <class V, class Access>
  Key<S> variant(std::string name, Access access, Value<V> value, std::string doc) const {
    Key<S> key;
    key.info = keyInfo(std::move(name), std::move(doc), value);
    key.info.kind = true;
    key.info.presence = Presence::ValueRequired;
    key.holds = [access](const S& s) { return std::holds_alternative<V>(std::invoke(access, s)); };
    key.assign = [access, read = value.read](const Field& f, S& s, const ReadContext& ctx) {
      V v{};
      read(f, v, ctx);
      std::invoke(access, s) = std::move(v);
    };
    key.to_json = [access, write = value.write](const S& s) -> std::optional<json> {
      return write(std::get<V>(std::invoke(access, s)));
    };
    return key;
  }

  // The keys of Spec's struct written in this map, filling `access(s)`: a struct, or an optional one
  // that is set when the key `present_with` is given.
  template <auto Spec, class Access>
  Key<S> inlined(Access access, std::string present_with = {}) const {
    using Member = std::remove_cvref_t<std::invoke_result_t<Access, S&>>;
    Key<S> key;
    key.info.map = []() -> const MapInfo& { return Spec().info; };
    if constexpr (IsOptional<Member>::value) {
      key.info.default_text = "none";  // the reference's default for each of its keys
      key.assign = [access, present_with](const Field& map, S& s, const ReadContext& ctx) {
        typename Member::value_type v{};
        readKeys(Spec(), map, v, nullptr, ctx);
        if (map.has(present_with)) std::invoke(access, s) = std::move(v);
      };
      key.write_inline = [access](const S& s, json& out) {
        if (const auto& member = std::invoke(access, s)) writeKeys(Spec(), *member, out);
      };
    } else {
      key.assign = [access](const Field& map, S& s, const ReadContext& ctx) {
        readKeys(Spec(), map, std::invoke(access, s), nullptr, ctx);
      };
      key.write_inline = [access](const S& s, json& out) { writeKeys(Spec(), std::invoke(access, s), out); };
    }
    return key;
  }
};

// The preset's own table (preset/schema.cpp): the top-level map, and through it every other.
const MapSpec<Preset>& presetTable();

}  // namespace rockbake::schema
