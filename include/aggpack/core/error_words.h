#pragma once
// The sentences of aggpack's error messages, each declared once with its English words, so that a
// front end can word an error in its own language from the error's parts instead of parsing its
// text (aggpack-gui's catalogues have one entry per sentence; a missing one fails its test). An
// error's Wording is a sentence and the values ("{}" in order) that fill it.
//
// Two uses: the allowed part of InvalidInput, LimitExceeded and ConfigError ("finite and >= 0",
// ">= {} = {}"), and the whole message of IoError and FormatError ("cannot read {}: no such
// file"). kText is a free-form English text (its one value): errors not yet given a sentence.
// Values that name an options field ("shape.edge_length_ratio") are renamed to configuration
// keys by with_key_names (config/schema.h); so a field name is a value, never a sentence's word.
//
// No include guard on the list: AGGPACK_ERROR_SENTENCES(X) calls X(Name, "english") per sentence.

#include <string>
#include <vector>

// clang-format off
#define AGGPACK_ERROR_SENTENCES(X)                                                              \
  X(Text, "{}")                                                                                 \
  /* allowed values: rules of one value */                                                      \
  X(FiniteAtLeastZero, "finite and >= 0")                                                       \
  X(FinitePositive, "finite and > 0")                                                           \
  X(FiniteAtLeastZeroRelative, "finite and >= 0 (0 = relative, use {})")                       \
  /* rules between keys */                                                                      \
  X(AtLeastKey, ">= {} = {}")                                                                   \
  X(AtLeastKeyMetres, ">= {} = {} m")                                                           \
  X(AboveKey, "> {} = {}")                                                                      \
  X(AboveKeyMetres, "> {} = {} m")                                                              \
  X(EdgeLengthLattice,                                                                          \
    "> 0 with packer.kind = lattice; 0 = relative edge length exists only for the random "      \
    "packer")                                                                                   \
  X(SieveNeeded,                                                                                \
    "grading.kind = \"sieve\" needs grading.sieve = [[size_m, percent_passing], ...] (at "     \
    "least 2 rows)")                                                                            \
  X(BelowHalfExtent, "< half the smallest container extent ({} m)")                             \
  X(LatticeSpacing, "0 (= 2 radius + gap) or > radius + gap")                                   \
  X(LatticeSpacingAbove, "0 (= 2 radius + gap) or > radius + gap = {}")                         \
  X(RadiusFitsContainer,                                                                        \
    "small enough that a particle of diameter 2 R fits in the container (minus wall gaps)")     \
  X(RadiusOneSite, "small enough that at least one site fits in the container")                 \
  X(LatticeSites, "a radius giving at most 10^8 lattice sites (gives {})")                      \
  X(DensifyGapAtMostFill, "[0, {}], at most the fill's gap")                                    \
  X(FillRandomWhenFixed,                                                                        \
    "random with densify.mode = fixed and densify.target_fraction = {} > 0 (to compress a "     \
    "lattice packing: aggpack pack it, then aggpack densify it; or set "                        \
    "densify.target_fraction = 0)")                                                             \
  X(CountUnsetWhenFixed,                                                                        \
    "unset with densify.mode = fixed and densify.target_fraction = {} > 0 (use "                \
    "packer.target_fraction: the fill's fraction)")                                             \
  X(FillBelowTarget,                                                                            \
    "(0, {}), below densify.target_fraction: the fill runs in the container enlarged by "       \
    "(densify.target_fraction / packer.target_fraction)^(1/3) and is compressed into the "      \
    "given one")                                                                                \
  X(SieveRows, "at least 2 rows (size, percent passing)")                                       \
  X(SieveSizesIncrease, "> previous size {} (sizes strictly increasing)")                       \
  X(SievePassingRises, ">= previous {} (percent passing non-decreasing)")                       \
  X(SieveLastPassesAll, "100 (the largest sieve passes everything)")                            \
  X(SieveFirstRetains, "< 100 (some material must be retained on the smallest sieve)")          \
  X(LibraryNeedsRelativeLength,                                                                 \
    "0 when {} > 0 (a library rescales shapes, so L must be relative: set {} = 0 and use {})")  \
  X(LibrarySizeWithFiles, "0 when {} is given (shapes come from the files)")                   \
  X(VerticesNeeded, "a value needing at most {} = {} vertices (needs about {})")                \
  X(EdgeLengthForVertexCap,                                                                     \
    ">= about {} m for radius {} m: may need up to {} vertices, max_vertices is {}")            \
  X(VertexCapReached,                                                                           \
    "a larger cap or a longer edge_length (growth still had edges of {} m > L = {} m)")         \
  X(CountAtMostLibrary, "at most the library's {} shapes when {} = true")                       \
  X(LibraryShapesForSites,                                                                      \
    "at most the library's {} shapes for the lattice's {} sites (a smaller container, or a "    \
    "larger {})")                                                                               \
  X(LibraryReachesFraction,                                                                     \
    "a library whose {} shapes, each used once, reach {} = {} (they reach {})")                 \
  X(FractionReachable, "a target reachable with 10^8 particles")                                \
  X(FractionParticles, "a target needing at most 10^8 particles (needs more than {})")         \
  X(GradingFitsInterior, "particles that fit in the container's interior ({} m across)")       \
  /* whole messages: reading a file */                                                          \
  X(ReadNoSuchFile, "cannot read {}: no such file")                                             \
  X(ReadFolder, "cannot read {}: it is a folder")                                               \
  X(ReadPermission, "cannot read {}: permission denied")                                        \
  X(ReadSystemError, "cannot read {}: {}")                                                      \
  X(NotHdf5, "{}: not an HDF5 file (expected an aggpack packing, format {})")                   \
  X(Hdf5Unreadable, "{}: cannot open as HDF5 ({}; the file is truncated or corrupted)")         \
  X(NoFormatName, "{}: not an aggpack packing (no format_name attribute; expected {})")         \
  X(WrongFormatName, "{}: /format_name = {}: not an aggpack packing (expected \"{}\")")         \
  X(WrongFormatVersion,                                                                         \
    "{}: /format_version = {}: format version {} is not supported (this aggpack {} reads "      \
    "version {})")                                                                              \
  X(FieldCorrupt, "{}: {}: {} ({}; the file is truncated or corrupted)")                        \
  X(FieldInvalid, "{}: {}: {}")
// clang-format on

namespace aggpack {

/// One sentence of AGGPACK_ERROR_SENTENCES.
enum class Sentence {
#define AGGPACK_SENTENCE_ID(name, english) k##name,
  AGGPACK_ERROR_SENTENCES(AGGPACK_SENTENCE_ID)
#undef AGGPACK_SENTENCE_ID
      kCount
};

/// A sentence and its values, in order.
struct Wording {
  Sentence sentence = Sentence::kText;
  std::vector<std::string> values;
};

/// The sentence's English words with "{}" for each value ("finite and >= 0").
const char* english_words(Sentence sentence);

/// `words` with each "{}" replaced by the next of `values` (a missing value leaves "{}").
std::string fill_words(const char* words, const std::vector<std::string>& values);

/// The wording in English (the library's messages).
inline std::string english(const Wording& wording) {
  return fill_words(english_words(wording.sentence), wording.values);
}

}  // namespace aggpack
