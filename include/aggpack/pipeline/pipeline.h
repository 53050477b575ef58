#pragma once
// The one pipeline entry (issue 13): a configuration in, a packing with its provenance out. Every
// front end (CLI `pack`, the GUI, the repose/sweep fill) calls pack(); nothing else dispatches
// over packers or writes provenance.
//
// Packer kinds are the alternatives of PackerOptions, ONE list (aggpack/pack/packer_kinds.h:
// options structs with defaults and validate(), their words). Each kind's run function is one
// PackerRun specialisation in src/pipeline/pipeline.cpp; a kind without one fails to compile.

#include <optional>
#include <string_view>

#include "aggpack/config/config.h"
#include "aggpack/pack/dense_packer.h"
#include "aggpack/pack/packer_kinds.h"
#include "aggpack/pack/progress.h"

namespace aggpack {

/// The packer options a resolved configuration selects.
PackerOptions packer_options(const PackConfig& config);

/// What pack() made. `report` is the packer's report (for "dense": the fill's counts and times,
/// with container_volume, solid_fraction and stop_reason of the final, densified packing);
/// `densify` is set for the "dense" kind unless the fill was cancelled.
struct PipelineResult : PackResult {
  std::optional<DensifyReport> densify{};
};

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
