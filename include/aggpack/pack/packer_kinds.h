#pragma once
// The packer kinds, ONE list (issue 13): each kind is an options struct with defaults and a
// validate() naming "<kind>.<option>"; PackerOptions holds one of them. Declared here, below
// the config module, so that the config schema can bind keys to them; the pipeline
// (aggpack/pipeline/pipeline.h) runs them. A new kind: its options struct, one alternative of
// PackerOptions, its word in packer_kinds.cpp and its run function in src/pipeline/ (each a
// compile error when missing).

#include <cstdint>
#include <string>
#include <string_view>
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

/// \throw InvalidInput / LimitExceeded naming the key, as the kind's validate().
void validate(const PackerOptions& options);

}  // namespace aggpack
