#pragma once
// The packer kinds, ONE list (issue 13): each kind is an options struct with defaults and a
// validate() naming "<kind>.<option>"; PackerOptions holds one of them. Declared here, below
// the config module, so that the config schema can bind keys to them; the pipeline
// (aggpack/pipeline/pipeline.h) runs them. A new kind: its options struct (with `seed` and
// `container` members, or a `fill` of other kinds; optionally `grading`), one alternative of
// PackerOptions, its word in packer_kinds.cpp and its run function in src/pipeline/ (each a
// compile error when missing); its keys in the config schema.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "aggpack/pack/dense_packer.h"
#include "aggpack/pack/lattice_packer.h"
#include "aggpack/pack/random_packer.h"

namespace aggpack {

/// The "dense" packer kind: a fill (random sequential addition or the lattice) densified by
/// hard-particle Monte Carlo (dense_packer.h). Keys: the fill's own keys plus "densify.<option>".
struct DensePackOptions {
  std::variant<RandomPackOptions, LatticeOptions> fill = RandomPackOptions{};
  /// densify.gap must not exceed the fill's gap (the fill is the densifier's start packing);
  /// densify.seed seeds the Monte Carlo streams (a config binds it to packer.seed).
  DensifyOptions densify{};
};

/// \throw InvalidInput naming the key ("random.count", "densify.gap", ...), LimitExceeded; as the
///        fill's and the densifier's validate().
void validate(const DensePackOptions& options);

/// Every packer kind, one alternative each. The first is the default (the paper's case).
using PackerOptions = std::variant<LatticeOptions, RandomPackOptions, DensePackOptions>;

/// Word of each kind ("lattice", "random", "dense"), in PackerOptions order.
const std::vector<std::string>& packer_kind_names();

/// The kind's word: "lattice", "random", "dense".
std::string packer_kind_name(const PackerOptions& options);

/// A kind's default options from its word. \throw InvalidInput naming `key` (e.g. "packer.kind")
///        with the allowed words.
PackerOptions default_packer_options(std::string_view word, std::string_view key = "packer.kind");

/// The master seed of a kind's options (the fill's for "dense").
std::uint64_t packer_seed(const PackerOptions& options);

/// The densifier's seed that a configuration derives from packer.seed for the "dense" kind
/// (the fill keeps packer.seed). Different from it so that the densifier's streams (seed,
/// sweep << 32 | particle) never repeat the fill's streams (seed, i); deterministic, < 2^63.
std::uint64_t derived_densify_seed(std::uint64_t packer_seed);

/// The container of a kind's options (the fill's for "dense").
const Container& packer_container(const PackerOptions& options);
Container& packer_container(PackerOptions& options);

/// The grading a kind's packing aims at: its `grading` member (the random packer's, also as the
/// fill of "dense"); none for a kind without one (lattice).
std::optional<Grading> packer_grading(const PackerOptions& options);

namespace packer_kinds_detail {
template <class T>
inline constexpr bool kIsVariant = false;
template <class... Ts>
inline constexpr bool kIsVariant<std::variant<Ts...>> = true;

template <class O, class T>
auto find_in(T& holder) {
  using Result = std::conditional_t<std::is_const_v<T>, const O*, O*>;
  using Plain = std::remove_const_t<T>;
  if constexpr (std::is_same_v<Plain, O>) {
    return static_cast<Result>(&holder);
  } else if constexpr (kIsVariant<Plain>) {
    return std::visit([](auto& part) -> Result { return find_in<O>(part); }, holder);
  } else if constexpr (std::is_same_v<Plain, DensePackOptions>) {
    const Result in_fill = find_in<O>(holder.fill);
    return in_fill != nullptr ? in_fill : find_in<O>(holder.densify);
  } else {
    return static_cast<Result>(nullptr);
  }
}
}  // namespace packer_kinds_detail

/// The options struct `O` where the chosen kind holds it: the kind's own options, or a part of
/// them (the "dense" kind's fill and DensifyOptions); null when the kind has none. The config
/// schema binds keys through it, so a key of the random packer also sets a dense random fill.
template <class O>
O* find_options(PackerOptions& options) {
  return packer_kinds_detail::find_in<O>(options);
}
template <class O>
const O* find_options(const PackerOptions& options) {
  return packer_kinds_detail::find_in<O>(options);
}

/// `O` as the kinds' defaults hold it: found in the first default-constructed kind that has one
/// (RandomPackOptions{} for the random keys, DensePackOptions{}.densify for the densify keys).
template <class O>
const O& default_options() {
  static const O defaults = [] {
    O found{};
    bool is_found = false;
    const auto look = [&](const auto& kind) {
      const PackerOptions options{kind};
      if (const O* o = find_options<O>(options); o != nullptr && !is_found) {
        found = *o;
        is_found = true;
      }
    };
    [&]<std::size_t... I>(std::index_sequence<I...>) {
      (look(std::variant_alternative_t<I, PackerOptions>{}), ...);
    }
    (std::make_index_sequence<std::variant_size_v<PackerOptions>>{});
    return found;
  }();
  return defaults;
}

/// \throw InvalidInput / LimitExceeded naming the key, as the kind's validate().
void validate(const PackerOptions& options);

}  // namespace aggpack
