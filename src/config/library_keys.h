#pragma once
// The options of a shape library (aggpack/shape/shape_library.h), declared once for every schema
// that has a library key: pack's particle.library_* and repose's and sweep's (the same names).
// Each schema binds them its own way (pack: on the packer kind's options; repose: a member).

#include <string>
#include <vector>

#include "aggpack/config/schema.h"
#include "aggpack/core/error_words.h"

namespace aggpack::config_detail {

/// The keys `prefix`library_units, _skip_bad, _max_hull_excess, _max_vertices and _use_once, in
/// that order, applying in `scope`. `bind_member` turns an accessor of ShapeLibraryOptions
/// (`[](auto& o) -> auto& { return o.import.units; }`) into the schema's binding; `use_once_doc`
/// ends the use-once key's line (what must hold as many shapes).
template <class Target, class BindMember>
std::vector<Key<Target>> library_option_keys(const std::string& prefix, const Scope<Target>& scope,
                                             const std::string& use_once_doc,
                                             BindMember bind_member) {
  return {
      {.name = prefix + "library_units",
       .type = ValueType::kWord,
       .words = {"mm", "m"},
       .scope = scope,
       .doc = "the length unit of the mesh files' coordinates",
       .binding = bind_member([](auto& o) -> auto& { return o.import.units; })},
      {.name = prefix + "library_skip_bad",
       .type = ValueType::kBool,
       .unit = "-",
       .scope = scope,
       .doc = "skip (and count) mesh files that are open, non-manifold, degenerate or over the "
              "hull limit, instead of stopping at the first",
       .binding = bind_member([](auto& o) -> auto& { return o.is_skipping_bad; })},
      {.name = prefix + "library_max_hull_excess",
       .unit = "-",
       .range = closed(0, 100),
       .scope = scope,
       .doc = "refuse a shape whose convex hull adds more than this fraction of its volume "
              "((V_hull - V) / V); 0 = no limit",
       .binding = bind_member([](auto& o) -> auto& { return o.import.max_hull_excess; }),
       .fields = {"particle.library_max_hull_excess"}},
      {.name = prefix + "library_max_vertices",
       .type = ValueType::kInteger,
       .range = closed(4, 1e6),
       .scope = scope,
       .doc = "hulls with more vertices are simplified to at most this many (inscribed; the "
              "volume change is reported)",
       .binding = bind_member([](auto& o) -> auto& { return o.import.max_vertices; }),
       .fields = {"particle.library_max_vertices"}},
      {.name = prefix + "library_use_once",
       .type = ValueType::kBool,
       .unit = "-",
       .scope = scope,
       .doc = "place each library shape at most once (in a seeded random order); " + use_once_doc,
       .binding = bind_member([](auto& o) -> auto& { return o.is_use_once; })},
  };
}

}  // namespace aggpack::config_detail
