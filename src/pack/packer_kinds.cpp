#include "aggpack/pack/packer_kinds.h"

#include <cstddef>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>

#include "aggpack/core/error.h"
#include "aggpack/pack/container.h"

namespace aggpack {

namespace {

// The word of each kind. Declared, never defined: a PackerOptions alternative without a
// specialisation below fails to compile.
template <class Options>
struct KindWord;
template <>
struct KindWord<LatticeOptions> {
  static constexpr std::string_view kWord = "lattice";
};
template <>
struct KindWord<RandomPackOptions> {
  static constexpr std::string_view kWord = "random";
};
template <>
struct KindWord<DensePackOptions> {
  static constexpr std::string_view kWord = "dense";
};

template <std::size_t... I>
std::vector<std::string> kind_words(std::index_sequence<I...>) {
  return {std::string(KindWord<std::variant_alternative_t<I, PackerOptions>>::kWord)...};
}

template <std::size_t... I>
PackerOptions default_of(std::size_t index, std::index_sequence<I...>) {
  PackerOptions options;
  ((index == I ? (options = std::variant_alternative_t<I, PackerOptions>{}, 0) : 0), ...);
  return options;
}

constexpr auto kKinds = std::make_index_sequence<std::variant_size_v<PackerOptions>>{};

}  // namespace

void validate(const DensePackOptions& options) {
  refuse_periodic_bed(std::visit([](const auto& fill) { return fill.container; }, options.fill),
                      options.densify.mode);
  std::visit([](const auto& fill) { validate(fill); }, options.fill);
  validate(options.densify);
  const double gap = std::visit([](const auto& fill) { return fill.gap; }, options.fill);
  if (options.densify.gap > gap) {
    throw InvalidInput("densify.gap", format_value(options.densify.gap),
                       Wording{Sentence::kDensifyGapAtMostFill, {format_value(gap)}});
  }
  // Fixed mode with a fraction target ends in the given container: the random fill runs in it
  // enlarged by (densify.target_fraction / packer.target_fraction)^(1/3) (the pipeline).
  const double asked = options.densify.target_fraction;
  if (options.densify.mode != DensifyMode::kFixed || asked <= 0.0) return;
  if (std::holds_alternative<LatticeOptions>(options.fill)) {
    throw InvalidInput("packer.fill", "lattice",
                       Wording{Sentence::kFillRandomWhenFixed, {format_value(asked)}});
  }
  const auto& random = std::get<RandomPackOptions>(options.fill);
  if (random.target == PackTarget::kCount) {
    throw InvalidInput("random.count", format_value(static_cast<double>(random.count)),
                       Wording{Sentence::kCountUnsetWhenFixed, {format_value(asked)}});
  }
  if (random.volume_fraction >= asked) {
    throw InvalidInput("random.volume_fraction", format_value(random.volume_fraction),
                       Wording{Sentence::kFillBelowTarget, {format_value(asked)}});
  }
}

const std::vector<std::string>& packer_kind_names() {
  static const std::vector<std::string> names = kind_words(kKinds);
  return names;
}

std::string packer_kind_name(const PackerOptions& options) {
  return std::string(std::visit(
      [](const auto& o) { return KindWord<std::decay_t<decltype(o)>>::kWord; }, options));
}

PackerOptions default_packer_options(std::string_view word, std::string_view key) {
  const auto& names = packer_kind_names();
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (names[i] == word) return default_of(i, kKinds);
  }
  std::string allowed;
  for (const auto& name : names) allowed += (allowed.empty() ? "" : ", ") + name;
  throw InvalidInput(std::string(key), std::string(word), allowed);
}

namespace {

// A kind's seed and container: its own members, or its fill's (a kind without either fails to
// compile here).
template <class Options>
auto& container_of(Options& o) {
  if constexpr (requires { o.fill; }) {
    return std::visit(
        [](auto& fill) -> auto& { return container_of(fill); }, o.fill);
  } else {
    return o.container;
  }
}

template <class Options>
std::uint64_t seed_of(const Options& o) {
  if constexpr (requires { o.fill; }) {
    return std::visit([](const auto& fill) { return seed_of(fill); }, o.fill);
  } else {
    return o.seed;
  }
}

template <class Options>
std::optional<Grading> grading_of(const Options& o) {
  if constexpr (requires { o.fill; }) {
    return std::visit([](const auto& fill) { return grading_of(fill); }, o.fill);
  } else if constexpr (requires { o.grading; }) {
    return o.grading;
  } else {
    return std::nullopt;
  }
}

}  // namespace

std::uint64_t packer_seed(const PackerOptions& options) {
  return std::visit([](const auto& o) { return seed_of(o); }, options);
}

std::uint64_t derived_densify_seed(std::uint64_t packer_seed) {
  // One SplitMix64 step (Steele, Lea, Flood), top 63 bits.
  std::uint64_t z = packer_seed + 0x9E3779B97F4A7C15ULL;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return (z ^ (z >> 31)) >> 1;
}

const Container& packer_container(const PackerOptions& options) {
  return std::visit([](const auto& o) -> const Container& { return container_of(o); }, options);
}

Container& packer_container(PackerOptions& options) {
  return std::visit([](auto& o) -> Container& { return container_of(o); }, options);
}

std::optional<Grading> packer_grading(const PackerOptions& options) {
  return std::visit([](const auto& o) { return grading_of(o); }, options);
}

void validate(const PackerOptions& options) {
  std::visit([](const auto& o) { validate(o); }, options);
}

}  // namespace aggpack
