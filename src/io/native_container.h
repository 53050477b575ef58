#pragma once
// The /container group of the native file, shared by its writer (native.cpp), reader
// (native_read.cpp) and validate_packing (native_validate.cpp). The attributes come from
// container_kinds(): `kind` (the kind's word), then every parameter of every kind in list order
// (a kind's own values; the other kinds' defaults, stored but not used), then `wall_gap`; then,
// in a periodic box's file only, the string `periodic` (its axes: "x" ... "xyz").

#include <string>
#include <vector>

#include "aggpack/core/error.h"
#include "aggpack/pack/container.h"

namespace aggpack::native_detail {

/// Throws FormatError "SOURCE: FIELD: REASON" (Sentence::kFieldInvalid), the field (unless
/// kText) and the reason marked as sentences of their own (Error::worded_values), with `words`:
/// values of theirs that are sentences too ("a compound type").
[[noreturn]] void fail_field(const std::string& source, const Wording& field, const Wording& reason,
                             const std::vector<WordedValue>& words = {});

/// The values of the container's numeric attributes, in file order (see above).
std::vector<double> container_values(const Container& container);

/// Throws FormatError naming `source` and the first attribute out of range: the parameters of
/// `kind` must be in (0, 1e6] m, the others (and wall_gap) in [0, 1e6] m. `values` in file order.
void check_container_values(const ContainerKindInfo& kind, const std::vector<double>& values,
                            const std::string& source);

}  // namespace aggpack::native_detail
