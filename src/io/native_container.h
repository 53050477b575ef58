#pragma once
// The /container group of the native file, shared by its writer (native.cpp), reader
// (native_read.cpp) and validate_packing (native_validate.cpp). The attributes come from
// container_kinds(): `kind` (the kind's word), then every parameter of every kind in list order
// (a kind's own values; the other kinds' defaults, stored but not used), then `wall_gap`.

#include <string>
#include <vector>

#include "aggpack/pack/container.h"

namespace aggpack::native_detail {

/// The values of the container's numeric attributes, in file order (see above).
std::vector<double> container_values(const Container& container);

/// Throws FormatError naming `source` and the first attribute out of range: the parameters of
/// `kind` must be in (0, 1e6] m, the others (and wall_gap) in [0, 1e6] m. `values` in file order.
void check_container_values(const ContainerKindInfo& kind, const std::vector<double>& values,
                            const std::string& source);

}  // namespace aggpack::native_detail
