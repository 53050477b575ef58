#pragma once
// The one pipeline entry (issue 13): a configuration in, a packing with its provenance out. Every
// front end (CLI `pack`, the GUI, the repose/sweep fill) calls pack(); nothing else dispatches
// over packers or writes provenance.
//
// Packer kinds are the alternatives of PackerOptions, ONE list. Each kind is an options struct
// (with validate() naming "<kind>.<option>") plus one PackerTraits specialisation in
// src/pipeline/ giving its word and its run function; a kind without one fails to compile
// (std::visit with no fallback). A new packer: its options struct and run function in pack/, one
// alternative here, one PackerTraits specialisation, its keys in the config schema.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "aggpack/io/config.h"
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

/// \throw InvalidInput / LimitExceeded naming the key, as the kind's validate().
void validate(const PackerOptions& options);

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
/// `densify` the densifier's report.
/// \throw InvalidInput naming "densify.<option>" or "start packing".
PipelineResult densify_packing(Packing start, const DensifyOptions& options, std::string_view note,
                               const PackControl& control = {});

}  // namespace aggpack
