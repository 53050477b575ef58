#include "aggpack/pack/packer_kinds.h"

#include <cstddef>
#include <type_traits>
#include <utility>

#include "aggpack/core/error.h"
#include "aggpack/core/overloaded.h"

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
  std::visit([](const auto& fill) { validate(fill); }, options.fill);
  validate(options.densify);
  const double gap = std::visit([](const auto& fill) { return fill.gap; }, options.fill);
  if (options.densify.gap > gap) {
    throw InvalidInput("densify.gap", format_value(options.densify.gap),
                       "[0, " + format_value(gap) + "], at most the fill's gap");
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

std::uint64_t packer_seed(const PackerOptions& options) {
  return std::visit(Overloaded{[](const LatticeOptions& o) { return o.seed; },
                               [](const RandomPackOptions& o) { return o.seed; },
                               [](const DensePackOptions& o) {
                                 return std::visit([](const auto& fill) { return fill.seed; },
                                                   o.fill);
                               }},
                    options);
}

void validate(const PackerOptions& options) {
  std::visit(Overloaded{[](const LatticeOptions& o) { validate(o); },
                        [](const RandomPackOptions& o) { validate(o); },
                        [](const DensePackOptions& o) { validate(o); }},
             options);
}

}  // namespace aggpack
