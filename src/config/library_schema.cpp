// The particle.library keys: particle shapes from mesh files (aggpack/shape/shape_library.h,
// loaded by the pipeline). Kept apart from pack_schema.cpp, which lists them after particle.*.

#include "aggpack/config/config.h"
#include "pack_binding.h"

namespace aggpack::config_detail {

namespace {

using PackScope = Scope<PackConfig>;

const RandomPackOptions* random_of(const PackConfig& c) {
  return find_options<RandomPackOptions>(c.packer);
}
const ShapeFiles* files_of(const PackConfig& c) {
  if (const RandomPackOptions* random = random_of(c)) return &random->shape.files;
  if (const auto* lattice = find_options<LatticeOptions>(c.packer)) return &lattice->files;
  return nullptr;
}
const PackScope kLibrary{.text = "particle.library given", .applies = [](const PackConfig& c) {
                           const ShapeFiles* files = files_of(c);
                           return files != nullptr && files->is_used();
                         }};

}  // namespace

// particle.library and its options: shapes from mesh files (aggpack/shape/shape_library.h).
std::vector<Key<PackConfig>> library_keys() {
  return {
      {.name = "particle.library",
       .type = ValueType::kPathList,
       .written = kLibrary,
       .doc = "a folder of particle meshes (.stl, .obj, .ply), one such file, or an array of "
              "folders and files: every particle is one of them, as its convex hull, scaled to "
              "the grading's sieve size (enclosing diameter) and randomly turned; unset = grown "
              "particles",
       .binding = bind(
           on<LatticeOptions>([](auto& o) -> auto& { return o.files.options.paths; }),
           on<RandomPackOptions>([](auto& o) -> auto& { return o.shape.files.options.paths; })),
       .presence = Presence::kOptional,
       .default_text = {Sentence::kDefaultNone, {}}},
      {.name = "particle.library_units",
       .type = ValueType::kWord,
       .words = {"mm", "m"},
       .scope = kLibrary,
       .doc = "the length unit of the mesh files' coordinates",
       .binding =
           bind(on<LatticeOptions>([](auto& o) -> auto& { return o.files.options.import.units; }),
                on<RandomPackOptions>(
                    [](auto& o) -> auto& { return o.shape.files.options.import.units; }))},
      {.name = "particle.library_skip_bad",
       .type = ValueType::kBool,
       .unit = "-",
       .scope = kLibrary,
       .doc = "skip (and count) mesh files that are open, non-manifold, degenerate or over the "
              "hull limit, instead of stopping at the first",
       .binding = bind(
           on<LatticeOptions>([](auto& o) -> auto& { return o.files.options.is_skipping_bad; }),
           on<RandomPackOptions>(
               [](auto& o) -> auto& { return o.shape.files.options.is_skipping_bad; }))},
      {.name = "particle.library_max_hull_excess",
       .unit = "-",
       .range = closed(0, 100),
       .scope = kLibrary,
       .doc = "refuse a shape whose convex hull adds more than this fraction of its volume "
              "((V_hull - V) / V); 0 = no limit",
       .binding = bind(on<LatticeOptions>(
                           [](auto& o) -> auto& { return o.files.options.import.max_hull_excess; }),
                       on<RandomPackOptions>([](auto& o) -> auto& {
                         return o.shape.files.options.import.max_hull_excess;
                       })),
       .fields = {"particle.library_max_hull_excess"}},
      {.name = "particle.library_max_vertices",
       .type = ValueType::kInteger,
       .range = closed(4, 1e6),
       .scope = kLibrary,
       .doc = "hulls with more vertices are simplified to at most this many (inscribed; the "
              "volume change is reported)",
       .binding = bind(
           on<LatticeOptions>([](auto& o) -> auto& { return o.files.options.import.max_vertices; }),
           on<RandomPackOptions>(
               [](auto& o) -> auto& { return o.shape.files.options.import.max_vertices; })),
       .fields = {"particle.library_max_vertices"}},
      {.name = "particle.library_use_once",
       .type = ValueType::kBool,
       .unit = "-",
       .scope = kLibrary,
       .doc = "place each library shape at most once (in a seeded random order); the run needs "
              "at least as many shapes as particles",
       .binding =
           bind(on<LatticeOptions>([](auto& o) -> auto& { return o.files.options.is_use_once; }),
                on<RandomPackOptions>(
                    [](auto& o) -> auto& { return o.shape.files.options.is_use_once; }))},
  };
}

}  // namespace aggpack::config_detail
