// The values of the preset schema's table (preset/schema.cpp,
// docs/preset-reference.md): how a key's YAML becomes its member's type and
// that type becomes JSON, with what the reference says of it (a type, "number",
// and a range, "[0, 1]"). Numbers, whole numbers, names, vectors, and maps and lists of maps read
// by another table; the values with rules of their own are in
// preset/schema_rules.h. Each read reports through Field, so problems keep
// their file:line:column and key path. Internal to the preset stage.
#pragma once

#include <cmath>
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
auto mapValue() {
  using T = typename std::remove_cvref_t<decltype(Spec())>::Struct;
  return Value<T>{"map",
                  "",
                  []() -> const MapInfo& { return Spec().info; },
                  false,
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
auto listOfMaps(ListRules<typename std::remove_cvref_t<decltype(Spec())>::Struct> rules = {}) {
  using T = typename std::remove_cvref_t<decltype(Spec())>::Struct;
  const auto read = [rules](const Field& list, std::vector<T>& items, const ReadContext& ctx) {
    items.clear();
    const std::size_t n = list.size();
    if (n == 0 && rules.empty) list.fail(rules.empty);
    for (std::size_t i = 0; i < n; ++i) {
      const auto item = [&] {
        T value{};
        readMap(Spec(), list.item(i), value, items.empty() ? nullptr : &items.back(), ctx);
        items.push_back(std::move(value));
      };
      if (rules.items_apart)
        readPart(ctx.source, item);
      else
        item();
    }
    if (rules.after && items.size() == n) rules.after(list, items);
  };
  const auto write = [](const std::vector<T>& items) {
    json out = json::array();
    for (const T& item : items) out.push_back(writeMap(Spec(), item));
    return out;
  };
  return Value<std::vector<T>>{"list", "", []() -> const MapInfo& { return Spec().info; }, true, read, write};
}

// A list whose items are `item` or null (nothing there).
template <class T>
Value<std::vector<std::optional<T>>> listOfNullable(Value<T> item) {
  return {"list",
          "",
          item.map,
          true,
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

// A whole number as the reference writes it: 2048, 1 000 000, −360.
inline std::string docWhole(long long v) {
  if (v < 0) return "−" + docWhole(-v);
  const std::string digits = std::to_string(v);
  if (digits.size() <= 4) return digits;
  std::string grouped;
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) grouped.push_back(' ');
    grouped.push_back(digits[i]);
  }
  return grouped;
}
// A bound as the reference writes it: 10⁶ for a large power of ten, else as docWhole or formatNumber.
inline std::string docNumber(double v) {
  if (v < 0) return "−" + docNumber(-v);
  if (v >= 1e6 && v == std::floor(v)) {
    const int exponent = int(std::lround(std::log10(v)));
    if (std::pow(10.0, exponent) == v) {
      static const char* const kSuperscript[] = {"⁰", "¹", "²", "³", "⁴", "⁵", "⁶", "⁷", "⁸", "⁹"};
      std::string digits;
      for (const char c : std::to_string(exponent)) digits += kSuperscript[c - '0'];
      return "10" + digits;
    }
  }
  if (v == std::floor(v) && v < 1e15) return docWhole((long long)v);
  return formatNumber(v);
}

inline Value<double> number() {
  return {"number",      "", nullptr, false, [](const Field& f, double& v, const ReadContext&) { v = f.number(); },
          toJson<double>};
}
inline Value<double> numberIn(double lo, double hi, bool lo_open = false, bool hi_open = false) {
  return {"number",
          std::string(lo_open ? "(" : "[") + docNumber(lo) + ", " + docNumber(hi) + (hi_open ? ")" : "]"),
          nullptr,
          false,
          [=](const Field& f, double& v, const ReadContext&) { v = f.numberIn(lo, hi, lo_open, hi_open); },
          toJson<double>};
}
inline Value<double> positive() {
  return {"number",      "> 0", nullptr, false, [](const Field& f, double& v, const ReadContext&) { v = f.positive(); },
          toJson<double>};
}
// A length in world units: > 0 and at most kMaxWorldLength.
inline Value<double> length() {
  return {"length",      "", nullptr, false, [](const Field& f, double& v, const ReadContext&) { v = f.length(); },
          toJson<double>};
}
template <class I>
Value<I> integer(long long lo, long long hi) {
  return {"whole number",
          docWhole(lo) + " … " + docWhole(hi),
          nullptr,
          false,
          [=](const Field& f, I& v, const ReadContext&) { v = I(f.integer(lo, hi)); },
          toJson<I>};
}
inline Value<std::uint64_t> unsigned64() {
  return {"seed",
          "0 … 2⁶⁴ − 1",
          nullptr,
          false,
          [](const Field& f, std::uint64_t& v, const ReadContext&) { v = f.unsigned64(); },
          toJson<std::uint64_t>};
}
inline Value<bool> boolean() {
  return {"boolean",   "", nullptr, false, [](const Field& f, bool& v, const ReadContext&) { v = f.boolean(); },
          toJson<bool>};
}
// One of an enum's names (schema::enumNames).
template <class E>
Value<E> choice() {
  std::string type;
  for (const auto& name : namesOf<E>()) type += (type.empty() ? "`" : " | `") + name + "`";
  return {type,
          "",
          nullptr,
          false,
          [](const Field& f, E& v, const ReadContext&) { v = *valueNamed<E>(f.choice(namesOf<E>())); },
          [](const E& v) { return json(nameOf(v)); }};
}
// Three lengths (sizes, radii, half extents).
inline Value<Vec3d> lengths3() {
  return {"3 lengths",  "", nullptr, false, [](const Field& f, Vec3d& v, const ReadContext&) { v = f.positiveVec3(); },
          toJson<Vec3d>};
}
// A position: each coordinate within ±kMaxWorldLength.
inline Value<Vec3d> position() {
  return {"position",
          "each within ±" + docNumber(kMaxWorldLength),
          nullptr,
          false,
          [](const Field& f, Vec3d& v, const ReadContext&) { v = f.vec3(); },
          toJson<Vec3d>};
}

}  // namespace rockbake::schema
