#pragma once
// The one pipeline entry (issue 13): a configuration in, a packing with its provenance out. Every
// front end (CLI `pack`, the GUI, the repose/sweep fill) calls pack(); nothing else dispatches
// over packers or writes provenance.
//
// Packer kinds are the alternatives of PackerOptions, ONE list (aggpack/pack/packer_kinds.h:
// options structs with defaults and validate(), their words). Each kind's run function is one
// PackerRun specialisation in src/pipeline/pipeline.cpp; a kind without one fails to compile.

#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "aggpack/config/config.h"
#include "aggpack/pack/dense_packer.h"
#include "aggpack/pack/packer_kinds.h"
#include "aggpack/pack/progress.h"
#include "aggpack/shape/shape_library.h"
#ifdef AGGPACK_HAS_SIM
#endif

namespace aggpack {

/// The packer options a resolved configuration selects.
PackerOptions packer_options(const PackConfig& config);

/// The "dense" kind's fill as it ran. In fixed mode with densify.target_fraction d > 0 the fill
/// runs in the user's container scaled by k = (d / p)^(1/3) in every extent (p = the fill's
/// target fraction, packer.target_fraction), so its solid volume is about d x the user's
/// container volume, and the densifier compresses it into exactly the user's container.
struct DenseFill {
  PackReport report{};          ///< the fill's own report (its container, counts, fraction)
  Container container{};        ///< the container the fill ran in
  double scale = 1.0;           ///< k above; 1 when the fill ran in the user's container
  double asked_fraction = 0.0;  ///< d (fixed mode), 0 when no fraction was asked
  Container given{};            ///< the user's container (the final one when all went well)
};

/// What pack() made. `report` is the packer's report (for "dense": the fill's counts and times,
/// with container_volume, solid_fraction, is_target_reached and stop_reason of the final,
/// densified packing); `densify` and `fill` are set for the "dense" kind (densify unless the fill
/// was cancelled).
struct PipelineResult : PackResult {
  std::optional<DensifyReport> densify{};
  std::optional<DenseFill> fill{};
  /// particle.library as loaded (its summary for the front ends), or null for grown particles.
  std::shared_ptr<const ShapeLibrary> library{};
};

/// What a "dense" run fell short of, one sentence each, for the front ends to show as warnings
/// (empty when it reached what was asked, or for another kind): cancelled; the random fill
/// stopped below its target (fixed mode: the given container then holds less than asked); the
/// densifier stopped before its target (jammed, budget: the container may be larger than the
/// given one).
std::vector<std::string> dense_shortfalls(const PipelineResult& result);

/// The shortfalls of dense_shortfalls, for a front end that words them itself (its numbers are
/// the result's: fill->report, report, densify, packing.container, fill->given).
enum class DenseShortfall {
  kCancelled,        ///< cancelled; the packing holds the last verified state
  kFillBelowTarget,  ///< the random fill stopped below packer.target_fraction (enlarged)
  kDensifyStopped,   ///< the densifier stopped before its target (jammed, budget)
  kContainerLarger   ///< ... and the packing's container is larger than the given one
};
std::vector<DenseShortfall> dense_shortfall_kinds(const PipelineResult& result);

/// The "dense" kind's fill options as pack() runs them: in fixed mode with
/// densify.target_fraction > 0 the random fill's container enlarged by DenseFill::scale (same
/// wall_gap); otherwise the fill unchanged. \throw InvalidInput as validate(DensePackOptions).
std::variant<RandomPackOptions, LatticeOptions> dense_fill_options(const DensePackOptions& options);

/// Whether pack() runs the "dense" kind's fill enlarged and compresses it into the user's
/// container (fixed mode, densify.target_fraction > 0, random fill).
bool is_into_given_container(const DensePackOptions& options);

/// Runs the kind's packer and stamps the provenance: aggpack version, seed (packer_seed()),
/// packer (the kind's word), no configuration text. Progress stages: kShapes and kPlacement of
/// the packer; the "dense" kind then kDensify (placed = sweeps). A cancel stops the current
/// stage and returns what it has (report.stop_reason kCancelled).
/// \throw InvalidInput / LimitExceeded naming the key (validate()).
PipelineResult pack(const PackerOptions& options, const PackControl& control = {});

/// pack(packer_options(config), control), with the provenance of the configuration: the
/// resolved TOML (config.resolved_toml), config.seed() and config.packer_name().
/// Timings stay in the report; the native file holds only what reproduces the packing.
PipelineResult pack(const PackConfig& config, const PackControl& control = {});

/// Continues from a saved packing (`aggpack densify in.h5`): densify() on `start`, with the
/// provenance of the continued run: the start's configuration text followed by `note` (the
/// densify options, e.g. as TOML comments), the densify seed, packer "dense". `report` holds
/// the final counts, container volume and solid fraction (stop_reason kCancelled when cancelled);
/// `densify` the densifier's report, which says why it stopped.
/// \throw InvalidInput naming "densify.<option>" or "start packing".
PipelineResult densify_packing(Packing start, const DensifyOptions& options, std::string_view note,
                               const PackControl& control = {});

}  // namespace aggpack
