#pragma once
// Bindings of pack keys to the options structs a packer kind holds (find_options,
// aggpack/pack/packer_kinds.h), and the key lists kept in files of their own.

#include <type_traits>
#include <vector>

#include "aggpack/config/config.h"
#include "binding.h"

namespace aggpack::config_detail {

// An accessor of one member of the options struct O: `on<LatticeOptions>([](auto& o) -> auto& {
// return o.alpha; })`.
template <class O, class Access>
struct On {
  Access access;
};
template <class O, class Access>
On<O, Access> on(Access access) {
  return {access};
}

template <class O, class Access>
const O* find_options_of(const On<O, Access>& /*member*/, const PackConfig& c) {
  return find_options<O>(c.packer);
}

template <class O, class Access>
Value get_on(const On<O, Access>& member, const PackConfig& c) {
  const O* o = find_options<O>(c.packer);
  return to_value(member.access(o != nullptr ? *o : default_options<O>()));
}

template <class O, class Access>
void set_on(const On<O, Access>& member, PackConfig& c, const Value& value) {
  if (O* o = find_options<O>(c.packer)) {
    using X = std::remove_cvref_t<decltype(member.access(*o))>;
    member.access(*o) = from_value<X>(value);
  }
}

// The first of `members` whose options struct the chosen kind holds, else `fallback`'s default.
template <class Fallback, class Member, class... Rest>
Value get_held(const PackConfig& c, const Fallback& fallback, const Member& member,
               const Rest&... rest) {
  if (find_options_of(member, c) != nullptr) return get_on(member, c);
  if constexpr (sizeof...(Rest) == 0) {
    return get_on(fallback, c);
  } else {
    return get_held(c, fallback, rest...);
  }
}

// A key bound to members of options structs: set on each struct the chosen kind holds (find_
// options: the kind's own options or its parts, such as the dense kind's fill); read from the
// first one it holds, else from the first's defaults (default_options), which is the key's
// default.
template <class First, class... Rest>
Binding<PackConfig> bind(First first, Rest... rest) {
  return {.get = [first, rest...](const PackConfig& c) -> Value {
            return get_held(c, first, first, rest...);
          },
          .set =
              [first, rest...](PackConfig& c, const Value& value) {
                set_on(first, c, value);
                (set_on(rest, c, value), ...);
              }};
}

/// The dense kind's keys: the [densify] table (src/config/densify_schema.cpp).
std::vector<Key<PackConfig>> densify_keys();

/// particle.library and its options (src/config/library_schema.cpp).
std::vector<Key<PackConfig>> library_keys();

}  // namespace aggpack::config_detail
