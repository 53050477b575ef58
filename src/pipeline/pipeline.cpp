#include "aggpack/pipeline/pipeline.h"

#include <string>
#include <type_traits>
#include <utility>

#include "aggpack/core/error.h"

namespace aggpack {

namespace {

// One packer kind's run function. Declared, never defined: a PackerOptions alternative
// without a specialisation below fails to compile.
template <class Options>
struct PackerRun;

template <>
struct PackerRun<LatticeOptions> {
  static PipelineResult run(const LatticeOptions& o, const PackControl& control) {
    PipelineResult result;
    static_cast<PackResult&>(result) = pack_lattice(o, control);
    return result;
  }
};

template <>
struct PackerRun<RandomPackOptions> {
  static PipelineResult run(const RandomPackOptions& o, const PackControl& control) {
    PipelineResult result;
    static_cast<PackResult&>(result) = pack_random(o, control);
    return result;
  }
};

template <>
struct PackerRun<DensePackOptions> {
  static PipelineResult run(const DensePackOptions& o, const PackControl& control) {
    validate(o);  // all of it before the fill runs
    PipelineResult result = std::visit(
        [&](const auto& fill) {
          return PackerRun<std::decay_t<decltype(fill)>>::run(fill, control);
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

// The one place provenance is written.
void stamp_provenance(Packing& packing, std::string_view packer, std::uint64_t seed,
                      std::string config_toml) {
  packing.provenance.aggpack_version = AGGPACK_VERSION;
  packing.provenance.config_toml = std::move(config_toml);
  packing.provenance.seed = seed;
  packing.provenance.packer = std::string(packer);
}

}  // namespace

PackerOptions packer_options(const PackConfig& config) { return config.packer; }

PipelineResult pack(const PackerOptions& options, const PackControl& control) {
  // Every packer validates its options first (the key named in the error).
  PipelineResult result = std::visit(
      [&](const auto& o) { return PackerRun<std::decay_t<decltype(o)>>::run(o, control); },
      options);
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
  stamp_provenance(result.packing, packer_kind_name(PackerOptions{DensePackOptions{}}),
                   options.seed, std::move(config_toml));
  return result;
}

}  // namespace aggpack
