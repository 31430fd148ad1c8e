// The values of the preset schema's table (preset/schema.cpp,
// docs/preset-reference.md): how a key's YAML becomes its member's type and
// that type becomes JSON, with what the reference says of it ("number in [0,
// 1]"). Numbers, whole numbers, names, vectors, and maps and lists of maps read
// by another table; the values with rules of their own are in
// preset/schema_rules.h. Each read reports through Field, so problems keep
// their file:line:column and key path. Internal to the preset stage.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "preset/schema_spec.h"
#include "preset/yaml_text.h"

namespace rockbake::schema {

template <class T>
json toJson(const T& value) {
  return json(value);
}

// A map read by Spec (a function returning a MapSpec), into the struct as it is.
template <auto Spec>
auto mapValue(std::string text = "map") {
  using T = typename std::remove_cvref_t<decltype(Spec())>::Struct;
  return Value<T>{std::move(text), []() -> const MapInfo& { return Spec().info; }, false,
                  [](const Field& f, T& t, const ReadContext& ctx) { readMap(Spec(), f, t, nullptr, ctx); },
                  [](const T& t) { return writeMap(Spec(), t); }};
}

template <class T>
struct ListRules {
  const char* empty = nullptr;  // an empty list is refused with this problem
  bool items_apart = false;     // each item is read as its own part (lint lists every item's problems)
  void (*after)(const Field& list, const std::vector<T>& items) = nullptr;  // once every item was read
};

// A list of maps read by Spec; each item's checks see the item before it.
template <auto Spec>
auto listOfMaps(ListRules<typename std::remove_cvref_t<decltype(Spec())>::Struct> rules = {},
                std::string text = "list of maps") {
  using T = typename std::remove_cvref_t<decltype(Spec())>::Struct;
  return Value<std::vector<T>>{std::move(text), []() -> const MapInfo& { return Spec().info; }, true,
                               [rules](const Field& list, std::vector<T>& items, const ReadContext& ctx) {
                                 items.clear();
                                 const std::size_t n = list.size();
                                 if (n == 0 && rules.empty) list.fail(rules.empty);
                                 for (std::size_t i = 0; i < n; ++i) {
                                   const auto read = [&] {
                                     T item{};
                                     readMap(Spec(), list.item(i), item, items.empty() ? nullptr : &items.back(), ctx);
                                     items.push_back(std::move(item));
                                   };
                                   if (rules.items_apart)
                                     readPart(ctx.source, read);
                                   else
                                     read();
                                 }
                                 if (rules.after && items.size() == n) rules.after(list, items);
                               },
                               [](const std::vector<T>& items) {
                                 json out = json::array();
                                 for (const T& item : items) out.push_back(writeMap(Spec(), item));
                                 return out;
                               }};
}

// A list whose items are `item` or null (nothing there).
template <class T>
Value<std::vector<std::optional<T>>> listOfNullable(Value<T> item, std::string text) {
  return {std::move(text), item.map, true,
          [read = item.read](const Field& list, std::vector<std::optional<T>>& items, const ReadContext& ctx) {
            items.clear();
            for (std::size_t i = 0; i < list.size(); ++i) {
              const Field f = list.item(i);
              if (!f.defined()) {
                items.push_back(std::nullopt);
                continue;
              }
              T value{};
              read(f, value, ctx);
              items.push_back(std::move(value));
            }
          },
          [write = item.write](const std::vector<std::optional<T>>& items) {
            json out = json::array();
            for (const auto& value : items) out.push_back(value ? write(*value) : json(nullptr));
            return out;
          }};
}

inline Value<double> number() {
  return {"number", nullptr, false, [](const Field& f, double& v, const ReadContext&) { v = f.number(); },
          toJson<double>};
}
inline Value<double> numberIn(double lo, double hi, bool lo_open = false, bool hi_open = false) {
  return {"number in " + std::string(lo_open ? "(" : "[") + formatNumber(lo) + ", " + formatNumber(hi) +
              (hi_open ? ")" : "]"),
          nullptr, false,
          [=](const Field& f, double& v, const ReadContext&) { v = f.numberIn(lo, hi, lo_open, hi_open); },
          toJson<double>};
}
inline Value<double> positive() {
  return {"number > 0", nullptr, false, [](const Field& f, double& v, const ReadContext&) { v = f.positive(); },
          toJson<double>};
}
// A length in world units: > 0 and at most kMaxWorldLength.
inline Value<double> length() {
  return {"number > 0, at most " + formatNumber(kMaxWorldLength), nullptr, false,
          [](const Field& f, double& v, const ReadContext&) { v = f.length(); }, toJson<double>};
}
template <class I>
Value<I> integer(long long lo, long long hi) {
  return {"whole number " + std::to_string(lo) + " to " + std::to_string(hi), nullptr, false,
          [=](const Field& f, I& v, const ReadContext&) { v = I(f.integer(lo, hi)); }, toJson<I>};
}
inline Value<std::uint64_t> unsigned64() {
  return {"whole number >= 0", nullptr, false,
          [](const Field& f, std::uint64_t& v, const ReadContext&) { v = f.unsigned64(); }, toJson<std::uint64_t>};
}
inline Value<bool> boolean() {
  return {"true or false", nullptr, false, [](const Field& f, bool& v, const ReadContext&) { v = f.boolean(); },
          toJson<bool>};
}
// One of an enum's names (schema::enumNames).
template <class E>
Value<E> choice() {
  return {"one of: " + joinNames(namesOf<E>()), nullptr, false,
          [](const Field& f, E& v, const ReadContext&) { v = *valueNamed<E>(f.choice(namesOf<E>())); },
          [](const E& v) { return json(nameOf(v)); }};
}
// Three lengths (sizes, radii, half extents).
inline Value<Vec3d> lengths3() {
  return {"[x, y, z], each > 0, at most " + formatNumber(kMaxWorldLength), nullptr, false,
          [](const Field& f, Vec3d& v, const ReadContext&) { v = f.positiveVec3(); }, toJson<Vec3d>};
}
// A position: each coordinate within ±kMaxWorldLength.
inline Value<Vec3d> position() {
  return {"[x, y, z], each within ±" + formatNumber(kMaxWorldLength), nullptr, false,
          [](const Field& f, Vec3d& v, const ReadContext&) { v = f.vec3(); }, toJson<Vec3d>};
}

}  // namespace rockbake::schema
