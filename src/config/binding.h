#pragma once
// Bindings of schema keys to options-struct members: `members<Target>(access, ...)` sets every
// listed member and reads the first. An accessor is a generic lambda returning a reference,
// `[](auto& o) -> auto& { return o.lattice.alpha; }`, so it serves both get (const) and set.

#include <cstdint>
#include <string>
#include <type_traits>
#include <vector>

#include "aggpack/config/schema.h"
#include "aggpack/shape/generator.h"
#include "aggpack/shape/shape_library.h"

namespace aggpack::config_detail {

template <typename X>
Value to_value(const X& x) {
  if constexpr (std::is_same_v<X, double> || std::is_same_v<X, bool>) {
    return x;
  } else if constexpr (std::is_same_v<X, Growth>) {
    return std::string(growth_name(x));
  } else if constexpr (std::is_same_v<X, LengthUnit>) {
    return std::string(length_unit_name(x));
  } else if constexpr (std::is_integral_v<X>) {
    return static_cast<std::int64_t>(x);
  } else {
    return x;
  }
}

template <typename X>
X from_value(const Value& value) {
  if constexpr (std::is_same_v<X, double> || std::is_same_v<X, bool>) {
    return std::get<X>(value);
  } else if constexpr (std::is_same_v<X, Growth>) {  // a word the schema has checked
    return find_growth(std::get<std::string>(value)).value_or(Growth::kHull);
  } else if constexpr (std::is_same_v<X, LengthUnit>) {  // a word the schema has checked
    return std::get<std::string>(value) == "m" ? LengthUnit::kMetre : LengthUnit::kMillimetre;
  } else if constexpr (std::is_integral_v<X>) {
    return static_cast<X>(std::get<std::int64_t>(value));
  } else {
    return std::get<X>(value);
  }
}

template <typename Target, typename First, typename... Rest>
Binding<Target> members(First first, Rest... rest) {
  return {.get = [first](const Target& target) { return to_value(first(target)); },
          .set =
              [first, rest...](Target& target, const Value& value) {
                using X = std::remove_cvref_t<decltype(first(target))>;
                const X x = from_value<X>(value);
                first(target) = x;
                ((rest(target) = static_cast<std::remove_cvref_t<decltype(rest(target))>>(x)), ...);
              }};
}

/// A key's default: its binding read on the options' defaults.
template <typename Target>
void fill_defaults(Schema<Target>& schema, const Target& defaults) {
  for (auto& key : schema.keys) {
    if (!key.default_value) key.default_value = key.binding.get(defaults);
  }
}

}  // namespace aggpack::config_detail
