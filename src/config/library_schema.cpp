// The particle.library keys: particle shapes from mesh files (aggpack/shape/shape_library.h,
// loaded by the pipeline). Kept apart from pack_schema.cpp, which lists them after particle.*.

#include "aggpack/config/config.h"
#include "library_keys.h"
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
  std::vector<Key<PackConfig>> keys = {
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
  };
  // Its options, bound on both packer kinds' library options.
  for (auto& key : library_option_keys<PackConfig>(
           "particle.", kLibrary, "the run needs at least as many shapes as particles",
           [](auto member) {
             return bind(
                 on<LatticeOptions>([member](auto& o) -> auto& { return member(o.files.options); }),
                 on<RandomPackOptions>([member](auto& o) -> auto& {
                   return member(o.shape.files.options);
                 }));
           })) {
    keys.push_back(std::move(key));
  }
  return keys;
}

}  // namespace aggpack::config_detail
