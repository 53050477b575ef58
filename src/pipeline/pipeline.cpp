#include "aggpack/pipeline/pipeline.h"

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "aggpack/core/error.h"
#include "aggpack/io/shape_library_files.h"
#include "aggpack/pack/container.h"

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
    const auto fill_options = dense_fill_options(o);
    const bool is_enlarged = is_into_given_container(o);
    PipelineResult result = std::visit(
        [&](const auto& fill) {
          return PackerRun<std::decay_t<decltype(fill)>>::run(fill, control);
        },
        fill_options);
    DenseFill fill{
        .report = result.report,
        .container = result.packing.container,
        .scale = 1.0,
        .asked_fraction = o.densify.mode == DensifyMode::kFixed ? o.densify.target_fraction : 0.0,
        .given = packer_container(PackerOptions{o})};
    DensifyOptions densify_options = o.densify;
    if (is_enlarged) {
      // Compress into exactly the given container. A fill that jammed below its target holds
      // less than asked x the given volume: then only the container is the target (the fraction
      // reached is reported, lower than asked).
      const Container& given = fill.given;
      fill.scale = container_ratio(given, fill.container).x();
      densify_options.target_container = given;
      if (result.report.solid_volume < o.densify.target_fraction * given.volume()) {
        densify_options.target_fraction = 0.0;
      }
    }
    result.fill = fill;
    if (result.report.stop_reason == StopReason::kCancelled) return result;
    PackControl densify_control = control;
    if (control.on_progress) {
      densify_control.on_progress = [&control](const PackProgress& progress) {
        PackProgress staged = progress;
        staged.stage = PackStage::kDensify;
        control.on_progress(staged);
      };
    }
    DensifyResult dense = densify(std::move(result.packing), densify_options, densify_control);
    result.packing = std::move(dense.packing);
    PackReport& report = result.report;
    report.container_volume = result.packing.container.volume();
    report.solid_fraction = dense.report.solid_fraction;
    report.target_solid_fraction = fill.asked_fraction;
    const bool is_densified = dense.report.stop == DensifyStop::kTargetReached ||
                              dense.report.stop == DensifyStop::kSettled;
    report.is_target_reached =
        is_densified && report.solid_fraction >= fill.asked_fraction * (1 - 1e-9);
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

bool is_into_given_container(const DensePackOptions& options) {
  return options.densify.mode == DensifyMode::kFixed && options.densify.target_fraction > 0.0 &&
         std::holds_alternative<RandomPackOptions>(options.fill);
}

std::variant<RandomPackOptions, LatticeOptions> dense_fill_options(
    const DensePackOptions& options) {
  validate(options);  // packer.target_fraction < densify.target_fraction, a random fill, ...
  if (!is_into_given_container(options)) return options.fill;
  RandomPackOptions fill = std::get<RandomPackOptions>(options.fill);
  // Every extent by k = (d / p)^(1/3): the fill's target p in the enlarged container is a solid
  // volume of d x the given container's volume.
  const double scale = std::cbrt(options.densify.target_fraction / fill.volume_fraction);
  fill.container = container_scaled(fill.container, Vec3::Constant(scale));
  return fill;
}

PipelineResult pack(const PackerOptions& options, const PackControl& control) {
  // particle.library: the mesh files are read once here, for whichever options hold them (a
  // dense kind's fill too), and shared read-only by the packer.
  PackerOptions run_options = options;
  ShapeFiles* files = nullptr;
  if (auto* random = find_options<RandomPackOptions>(run_options)) {
    files = &random->shape.files;
  } else if (auto* lattice = find_options<LatticeOptions>(run_options)) {
    files = &lattice->files;
  }
  if (files != nullptr && files->is_used() && !files->loaded) {
    files->loaded = std::make_shared<const ShapeLibrary>(load_shape_library(files->options));
  }
  // Every packer validates its options first (the key named in the error).
  PipelineResult result = std::visit(
      [&](const auto& o) { return PackerRun<std::decay_t<decltype(o)>>::run(o, control); },
      run_options);
  stamp_provenance(result.packing, packer_kind_name(options), packer_seed(options), {});
  if (files != nullptr && files->loaded) {
    result.packing.provenance.shape_library = files->loaded->provenance(result.library_shapes);
    result.library = files->loaded;
  }
  return result;
}

std::vector<DenseShortfall> dense_shortfall_kinds(const PipelineResult& result) {
  std::vector<DenseShortfall> kinds;
  if (!result.fill) return kinds;
  const DenseFill& fill = *result.fill;
  if (result.report.stop_reason == StopReason::kCancelled) return {DenseShortfall::kCancelled};
  if (fill.scale != 1.0 && fill.report.stop_reason != StopReason::kTargetReached) {
    kinds.push_back(DenseShortfall::kFillBelowTarget);
  }
  if (!result.densify) return kinds;
  const DensifyStop stop = result.densify->stop;
  if (stop != DensifyStop::kTargetReached && stop != DensifyStop::kSettled) {
    kinds.push_back(DenseShortfall::kDensifyStopped);
    if (!(result.packing.container.shape == fill.given.shape)) {
      kinds.push_back(DenseShortfall::kContainerLarger);
    }
  }
  return kinds;
}

std::vector<std::string> dense_shortfalls(const PipelineResult& result) {
  std::vector<std::string> lines;
  char text[1024];
  for (const DenseShortfall kind : dense_shortfall_kinds(result)) {
    const DenseFill& fill = *result.fill;
    switch (kind) {
      case DenseShortfall::kCancelled:
        lines.emplace_back("cancelled; the packing holds the last verified state");
        break;
      case DenseShortfall::kFillBelowTarget:
        std::snprintf(text, sizeof text,
                      "the random fill stopped at %.4f solid, below packer.target_fraction %.4f in "
                      "the enlarged container (%s); compressed into the given container it is "
                      "%.4f solid, below densify.target_fraction %.4f (lower "
                      "packer.target_fraction or raise packer.attempts)",
                      fill.report.solid_fraction, fill.report.target_solid_fraction,
                      to_string(fill.report.stop_reason).c_str(), result.report.solid_fraction,
                      fill.asked_fraction);
        lines.emplace_back(text);
        break;
      case DenseShortfall::kDensifyStopped:
        lines.push_back("densify target not reached: " + result.densify->summary() +
                        "; the packing holds the densest verified state");
        break;
      case DenseShortfall::kContainerLarger:
        std::snprintf(text, sizeof text,
                      ", its container %.6g m^3, larger than the given %.6g m^3 (raise "
                      "densify.max_sweeps or lower densify.target_fraction)",
                      result.packing.container.volume(), fill.given.volume());
        lines.back() += text;
        break;
    }
  }
  return lines;
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
