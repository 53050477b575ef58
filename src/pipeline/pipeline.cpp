#include "aggpack/pipeline/pipeline.h"

#include <array>
#include <cstddef>
#include <type_traits>
#include <utility>

#include "aggpack/core/error.h"

namespace aggpack {

namespace {

template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};
template <class... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;

// One packer kind: its word, its seed and its run function. Declared, never defined: a
// PackerOptions alternative without a specialisation below fails to compile.
template <class Options>
struct PackerTraits;

template <>
struct PackerTraits<LatticeOptions> {
  static constexpr std::string_view kName = "lattice";
  static std::uint64_t seed(const LatticeOptions& o) { return o.seed; }
  static PipelineResult run(const LatticeOptions& o, const PackControl& control) {
    PipelineResult result;
    static_cast<PackResult&>(result) = pack_lattice(o, control);
    return result;
  }
};

template <>
struct PackerTraits<RandomPackOptions> {
  static constexpr std::string_view kName = "random";
  static std::uint64_t seed(const RandomPackOptions& o) { return o.seed; }
  static PipelineResult run(const RandomPackOptions& o, const PackControl& control) {
    PipelineResult result;
    static_cast<PackResult&>(result) = pack_random(o, control);
    return result;
  }
};

double fill_gap(const DensePackOptions& o) {
  return std::visit([](const auto& fill) { return fill.gap; }, o.fill);
}

template <>
struct PackerTraits<DensePackOptions> {
  static constexpr std::string_view kName = "dense";
  static std::uint64_t seed(const DensePackOptions& o) {
    return std::visit([](const auto& fill) { return fill.seed; }, o.fill);
  }
  static PipelineResult run(const DensePackOptions& o, const PackControl& control) {
    validate(o);  // all of it before the fill runs
    PipelineResult result = std::visit(
        [&](const auto& fill) {
          return PackerTraits<std::decay_t<decltype(fill)>>::run(fill, control);
        },
        o.fill);
    if (result.report.stop_reason == StopReason::kCancelled) return result;
    PackControl densify_control = control;
    if (control.on_progress) {
      densify_control.on_progress = [&control](const PackProgress& progress) {
        PackProgress staged = progress;
        staged.stage = PackStage::kDensify;
        control.on_progress(staged);
      };
    }
    DensifyResult dense = densify(std::move(result.packing), o.densify, densify_control);
    result.packing = std::move(dense.packing);
    PackReport& report = result.report;
    report.container_volume = result.packing.container.volume();
    report.solid_fraction = dense.report.solid_fraction;
    if (dense.report.stop == DensifyStop::kCancelled) {
      report.stop_reason = StopReason::kCancelled;
      report.is_target_reached = false;
    }
    result.densify = dense.report;
    return result;
  }
};

template <class Options>
using Traits = PackerTraits<std::decay_t<Options>>;

template <std::size_t... I>
std::vector<std::string> kind_names(std::index_sequence<I...>) {
  return {std::string(PackerTraits<std::variant_alternative_t<I, PackerOptions>>::kName)...};
}

template <std::size_t... I>
PackerOptions default_of(std::size_t index, std::index_sequence<I...>) {
  PackerOptions options;
  ((index == I ? (options = std::variant_alternative_t<I, PackerOptions>{}, 0) : 0), ...);
  return options;
}

// The one place provenance is written.
void stamp_provenance(Packing& packing, std::string_view packer, std::uint64_t seed,
                      std::string config_toml) {
  packing.provenance.aggpack_version = AGGPACK_VERSION;
  packing.provenance.config_toml = std::move(config_toml);
  packing.provenance.seed = seed;
  packing.provenance.packer = std::string(packer);
}

}  // namespace

void validate(const DensePackOptions& options) {
  std::visit([](const auto& fill) { validate(fill); }, options.fill);
  validate(options.densify);
  const double gap = fill_gap(options);
  if (options.densify.gap > gap) {
    throw InvalidInput("densify.gap", format_value(options.densify.gap),
                       "[0, " + format_value(gap) + "], at most the fill's gap");
  }
}

const std::vector<std::string>& packer_kind_names() {
  static const std::vector<std::string> names =
      kind_names(std::make_index_sequence<std::variant_size_v<PackerOptions>>{});
  return names;
}

std::string packer_kind_name(const PackerOptions& options) {
  return std::string(std::visit([](const auto& o) { return Traits<decltype(o)>::kName; }, options));
}

PackerOptions default_packer_options(std::string_view word, std::string_view key) {
  const auto& names = packer_kind_names();
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (names[i] == word) {
      return default_of(i, std::make_index_sequence<std::variant_size_v<PackerOptions>>{});
    }
  }
  std::string allowed;
  for (const auto& name : names) allowed += (allowed.empty() ? "" : ", ") + name;
  throw InvalidInput(std::string(key), std::string(word), allowed);
}

std::uint64_t packer_seed(const PackerOptions& options) {
  return std::visit([](const auto& o) { return Traits<decltype(o)>::seed(o); }, options);
}

void validate(const PackerOptions& options) {
  std::visit(Overloaded{[](const LatticeOptions& o) { validate(o); },
                        [](const RandomPackOptions& o) { validate(o); },
                        [](const DensePackOptions& o) { validate(o); }},
             options);
}

PackerOptions packer_options(const PackConfig& config) {
  switch (config.packer) {
    case PackerKind::kLattice:
      return config.lattice;
    case PackerKind::kRandom:
      return config.random;
  }
  throw InvalidInput("packer.kind", std::to_string(static_cast<int>(config.packer)),
                     "lattice, random");
}

PipelineResult pack(const PackerOptions& options, const PackControl& control) {
  // Every packer validates its options first (the key named in the error).
  PipelineResult result =
      std::visit([&](const auto& o) { return Traits<decltype(o)>::run(o, control); }, options);
  stamp_provenance(result.packing, packer_kind_name(options), packer_seed(options), {});
  return result;
}

PipelineResult pack(const PackConfig& config, const PackControl& control) {
  PipelineResult result = pack(packer_options(config), control);
  stamp_provenance(result.packing, config.packer_name(), config.seed(), config.resolved_toml);
  return result;
}

PipelineResult densify_packing(Packing start, const DensifyOptions& options, std::string_view note,
                               const PackControl& control) {
  std::string config_toml = start.provenance.config_toml + std::string(note);
  DensifyResult dense = densify(std::move(start), options, control);
  PipelineResult result;
  result.packing = std::move(dense.packing);
  PackReport& report = result.report;
  report.placed = result.packing.particles.size();
  report.requested = report.placed;
  report.container_volume = result.packing.container.volume();
  report.solid_fraction = dense.report.solid_fraction;
  report.solid_volume = report.solid_fraction * report.container_volume;
  report.placement_seconds = dense.report.seconds;
  report.is_target_reached = dense.report.stop == DensifyStop::kTargetReached ||
                             dense.report.stop == DensifyStop::kSettled;
  report.stop_reason = dense.report.stop == DensifyStop::kCancelled ? StopReason::kCancelled
                                                                    : StopReason::kTargetReached;
  result.densify = dense.report;
  stamp_provenance(result.packing, PackerTraits<DensePackOptions>::kName, options.seed,
                   std::move(config_toml));
  return result;
}

}  // namespace aggpack
