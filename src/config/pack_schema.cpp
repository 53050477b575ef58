// Every key of the pack configuration, declared once (see aggpack/config/schema.h). A new key is
// one entry here: its binding names the options member it sets, whose default is the key's.
// Container keys come from container_kinds(), output keys from output_format_names().

#include <numbers>
#include <optional>
#include <type_traits>
#include <utility>
#include <variant>

#include "aggpack/config/config.h"
#include "aggpack/io/export.h"
#include "aggpack/pack/container.h"
#include "pack_binding.h"

namespace aggpack {

namespace {

using config_detail::bind;
using config_detail::densify_keys;
using config_detail::get_on;
using config_detail::members;
using config_detail::on;
using config_detail::set_on;
using PackKey = Key<PackConfig>;
using PackScope = Scope<PackConfig>;

constexpr double kMaxSeed = 9223372036854775807.0;

const RandomPackOptions* random_of(const PackConfig& c) {
  return find_options<RandomPackOptions>(c.packer);
}
bool is_random(const PackConfig& c) { return random_of(c) != nullptr; }
bool is_lattice(const PackConfig& c) { return find_options<LatticeOptions>(c.packer) != nullptr; }
bool has_grading(const PackConfig& c, GradingKind kind) {
  return is_random(c) && random_of(c)->grading.kind == kind;
}

const PackScope kAlways{};
const PackScope kNever{.text = "never", .applies = [](const PackConfig&) { return false; }};
const PackScope kLattice{.text = "packer.kind = lattice or packer.fill = lattice",
                         .applies = is_lattice};
const PackScope kRandom{.text = "packer.kind = random or packer.fill = random",
                        .applies = is_random};
const PackScope kLatticeOrUniform{.text = "lattice, or random with grading.kind = uniform",
                                  .applies = [](const PackConfig& c) {
                                    return is_lattice(c) || has_grading(c, GradingKind::kUniform);
                                  }};
const PackScope kUniform{
    .text = "random with grading.kind = uniform",
    .applies = [](const PackConfig& c) { return has_grading(c, GradingKind::kUniform); }};
const PackScope kFuller{
    .text = "random with grading.kind = fuller",
    .applies = [](const PackConfig& c) { return has_grading(c, GradingKind::kFuller); }};
const PackScope kSieve{
    .text = "random with grading.kind = sieve",
    .applies = [](const PackConfig& c) { return has_grading(c, GradingKind::kSieve); }};
const PackScope kRelativeEdge{.text = "random with particle.edge_length = 0",
                              .applies = [](const PackConfig& c) {
                                return is_random(c) && random_of(c)->shape.edge_length == 0;
                              }};
const PackScope kCountTarget{.text = "random with packer.target_count",
                             .applies = [](const PackConfig& c) {
                               return is_random(c) && random_of(c)->target == PackTarget::kCount;
                             }};
const PackScope kFractionTarget{
    .text = "random without packer.target_count", .applies = [](const PackConfig& c) {
      return is_random(c) && random_of(c)->target == PackTarget::kVolumeFraction;
    }};
// The chosen kind's container (the dense kind's fill's).
template <typename Set>
void on_containers(PackConfig& c, Set set) {
  set(packer_container(c.packer));
}

std::vector<PackKey> container_keys() {
  std::vector<PackKey> keys;
  std::vector<std::string> words;
  std::string doc = "container shape:";
  for (const auto& info : container_kinds()) {
    words.emplace_back(info.name);
    doc += std::string(words.size() > 1 ? ", or " : " ") + info.description;
  }
  keys.push_back({.name = "container.kind",
                  .type = ValueType::kWord,
                  .words = words,
                  .doc = doc,
                  .binding = {.get = [](const PackConfig& c) -> Value {
                                return std::string(container_kind_info(c.container()).name);
                              },
                              .set =
                                  [](PackConfig& c, const Value& value) {
                                    // Another kind starts from that kind's defaults; its
                                    // params are set after this key (schema order).
                                    const ContainerKindInfo* info =
                                        find_container_kind(std::get<std::string>(value));
                                    if (info == nullptr) return;
                                    on_containers(c, [&](Container& k) {
                                      if (!info->holds(k)) k.shape = info->defaults.shape;
                                    });
                                  }}});
  for (const auto& info : container_kinds()) {
    const ContainerKindInfo* kind = &info;
    for (const auto& param : info.params) {
      const auto set = param.set;
      const auto get = param.get;
      keys.push_back(
          {.name = std::string("container.") + param.name,
           .unit = "m",
           .range = open_closed(0, kMaxMagnitude),
           .scope = {.text = std::string("container.kind = ") + info.name,
                     .applies = [kind](const PackConfig& c) { return kind->holds(c.container()); }},
           .doc = param.description,
           .binding = {.get = [get](const PackConfig& c) -> Value { return get(c.container()); },
                       .set =
                           [set](PackConfig& c, const Value& value) {
                             on_containers(c,
                                           [&](Container& k) { set(k, std::get<double>(value)); });
                           }},
           .default_value = get(info.defaults)});
    }
  }
  const ContainerKindInfo* box = find_container_kind(BoxContainer::kName);
  keys.push_back(
      {.name = "container.periodic",
       .type = ValueType::kWord,
       .words = periodic_words(),
       .scope = {.text = "container.kind = box",
                 .applies = [box](const PackConfig& c) { return box->holds(c.container()); }},
       // Written only when periodic, so that a resolved config of a walled box reads as before.
       .written = {.text = "container.periodic is not \"none\"",
                   .applies = [](const PackConfig& c) { return is_periodic(c.container()); }},
       .doc = "the box's periodic axes: a particle may cross such a face and meets the ones near "
              "the opposite face through its periodic image (random and dense packers)",
       .binding = {.get = [](const PackConfig& c) -> Value {
                     return periodic_word(periodic_axes(c.container()));
                   },
                   .set =
                       [](PackConfig& c, const Value& value) {
                         on_containers(c, [&](Container& k) {
                           if (auto* kind = k.get_if<BoxContainer>()) {
                             parse_periodic_word(std::get<std::string>(value), kind->periodic);
                           }
                         });
                       }},
       .default_value = std::string("none")});
  keys.push_back(
      {.name = "container.wall_gap",
       .unit = "m",
       .range = closed(0, kMaxMagnitude),
       .note = {Sentence::kBelowHalfSmallestExtent, {}},
       .doc = "minimum distance from every particle to every wall",
       .binding = {.get = [](const PackConfig& c) -> Value { return c.container().wall_gap; },
                   .set =
                       [](PackConfig& c, const Value& value) {
                         packer_container(c.packer).wall_gap = std::get<double>(value);
                       }}});
  return keys;
}

std::vector<PackKey> particle_keys() {
  return {
      {.name = "particle.alpha",
       .unit = "-",
       .range = closed(0, 1),
       .doc = "the paper's Eq. 3 shape control: 1 = regular, full shapes (octahedron-like); 0 = "
              "sharp, flat shapes",
       .binding = bind(on<LatticeOptions>([](auto& o) -> auto& { return o.alpha; }),
                       on<RandomPackOptions>([](auto& o) -> auto& { return o.shape.alpha; })),
       .fields = {"lattice.alpha", "shape.alpha"}},
      {.name = "particle.radius",
       .unit = "m",
       .range = open_closed(0, kMaxMagnitude),
       .scope = kLatticeOrUniform,
       .written = kLattice,
       .doc = "control radius R of every lattice particle; for the random packer the default of "
              "`radius_min` and `radius_max`",
       // A random packing keeps it as its smallest radius (set again by radius_min, whose
       // default it is), so that it reads back as the radius the grading was given.
       .binding =
           bind(on<LatticeOptions>([](auto& o) -> auto& { return o.radius; }),
                on<RandomPackOptions>([](auto& o) -> auto& { return o.grading.radius_min; })),
       .fields = {"lattice.radius"}},
      {.name = "particle.radius_min",
       .unit = "m",
       .range = open_closed(0, kMaxMagnitude),
       .note = {Sentence::kAtMost, {"radius_max"}},
       .scope = kUniform,
       .doc = "smallest control radius of the uniform grading (uniform by number)",
       .binding =
           bind(on<RandomPackOptions>([](auto& o) -> auto& { return o.grading.radius_min; })),
       .default_from = "particle.radius",
       .fields = {"grading.radius_min"}},
      {.name = "particle.radius_max",
       .unit = "m",
       .range = open_closed(0, kMaxMagnitude),
       .note = {Sentence::kAtLeast, {"radius_min"}},
       .scope = kUniform,
       .doc = "largest control radius of the uniform grading",
       .binding =
           bind(on<RandomPackOptions>([](auto& o) -> auto& { return o.grading.radius_max; })),
       .default_from = "particle.radius",
       .fields = {"grading.radius_max"}},
      {.name = "particle.edge_length",
       .unit = "m",
       .range = closed(0, kMaxMagnitude),
       .note = {Sentence::kZeroOnlyWith, {"packer.kind", "random"}},
       .doc = "growth edge-length control L: a particle grows on its longest edge until every "
              "edge is <= L. 0 = relative: L = `edge_length_ratio` x r for each particle (the "
              "same shape statistics at every size)",
       .binding = bind(on<LatticeOptions>([](auto& o) -> auto& { return o.edge_length; }),
                       on<RandomPackOptions>([](auto& o) -> auto& { return o.shape.edge_length; })),
       .fields = {"lattice.edge_length", "shape.edge_length", "edge_length"}},
      {.name = "particle.edge_length_ratio",
       .unit = "-",
       .range = closed(0.05, 10),
       .scope = kRelativeEdge,
       .doc = "L / r for each particle when particle.edge_length = 0",
       .binding =
           bind(on<RandomPackOptions>([](auto& o) -> auto& { return o.shape.edge_length_ratio; })),
       .fields = {"shape.edge_length_ratio"}},
      {.name = "particle.max_vertices",
       .type = ValueType::kInteger,
       .range = closed(6, 1e6),
       .doc = "vertex cap per particle; an L too small for the radius is rejected up front "
              "(LimitExceeded)",
       .binding =
           bind(on<LatticeOptions>([](auto& o) -> auto& { return o.max_vertices; }),
                on<RandomPackOptions>([](auto& o) -> auto& { return o.shape.max_vertices; })),
       .fields = {"lattice.max_vertices", "shape.max_vertices", "max_vertices"}},
      {.name = "particle.growth",
       .type = ValueType::kWord,
       .words = {growth_name(Growth::kHull), growth_name(Growth::kMidpoint)},
       .doc = "where growth puts a new vertex. hull (the paper's words): at a random point of "
              "the longest edge, out along the ray from the centre to its Eq. 3 distance, the "
              "convex hull kept; midpoint: aggpack 0.1's rule (edge midpoint, clamped onto the "
              "neighbouring faces; particles stay near the base octahedron), for earlier files",
       .binding =
           bind(on<LatticeOptions>([](auto& o) -> auto& { return o.form.growth; }),
                on<RandomPackOptions>([](auto& o) -> auto& { return o.shape.form.growth; }))},
      {.name = "particle.elongation",
       .unit = "-",
       .range = closed(0.1, 1),
       .doc = "control ellipsoid's intermediate / long semi-axis (1 = sphere; the long semi-axis "
              "is the control radius r): elongated particles",
       .binding =
           bind(on<LatticeOptions>([](auto& o) -> auto& { return o.form.elongation; }),
                on<RandomPackOptions>([](auto& o) -> auto& { return o.shape.form.elongation; })),
       .fields = {"elongation"}},
      {.name = "particle.flatness",
       .unit = "-",
       .range = closed(0.1, 1),
       .doc = "control ellipsoid's short / intermediate semi-axis (1 = sphere): flaky particles",
       .binding =
           bind(on<LatticeOptions>([](auto& o) -> auto& { return o.form.flatness; }),
                on<RandomPackOptions>([](auto& o) -> auto& { return o.shape.form.flatness; })),
       .fields = {"flatness"}},
      {.name = "particle.min_edge_ratio",
       .unit = "-",
       .range = closed(0, 0.5),
       .doc = "minimum edge length / L (hull growth): the random point on the longest edge is at "
              "least this x L from both ends (0 = anywhere, 0.5 = the midpoint)",
       .binding = bind(
           on<LatticeOptions>([](auto& o) -> auto& { return o.form.min_edge_ratio; }),
           on<RandomPackOptions>([](auto& o) -> auto& { return o.shape.form.min_edge_ratio; })),
       .fields = {"min_edge_ratio"}},
  };
}

std::vector<PackKey> grading_keys() {
  return {
      {.name = "grading.kind",
       .type = ValueType::kWord,
       .words = {to_string(GradingKind::kUniform), to_string(GradingKind::kFuller),
                 to_string(GradingKind::kSieve)},
       .scope = kRandom,
       .doc = "size distribution by volume (sizes are control diameters d = 2 r). uniform: r "
              "uniform by number in [`particle.radius_min`, `particle.radius_max`]; fuller: "
              "power law; sieve: a table",
       .binding = {
           .get = [](const PackConfig& c) -> Value {
             const RandomPackOptions* random = random_of(c);
             return to_string(
                 (random != nullptr ? *random : default_options<RandomPackOptions>()).grading.kind);
           },
           .set =
               [](PackConfig& c, const Value& value) {
                 auto* random = find_options<RandomPackOptions>(c.packer);
                 if (random == nullptr) return;
                 for (const auto kind :
                      {GradingKind::kUniform, GradingKind::kFuller, GradingKind::kSieve}) {
                   if (to_string(kind) == std::get<std::string>(value)) {
                     random->grading.kind = kind;
                   }
                 }
               }}},
      {.name = "grading.size_min",
       .unit = "m",
       .range = open_closed(0, kMaxMagnitude),
       .note = {Sentence::kBelow, {"size_max"}},
       .scope = kFuller,
       .doc = "Fuller curve: smallest control diameter d_min",
       .binding = bind(on<RandomPackOptions>([](auto& o) -> auto& { return o.grading.size_min; }))},
      {.name = "grading.size_max",
       .unit = "m",
       .range = open_closed(0, kMaxMagnitude),
       .note = {Sentence::kAbove, {"size_min"}},
       .scope = kFuller,
       .doc = "Fuller curve: largest control diameter d_max",
       .binding = bind(on<RandomPackOptions>([](auto& o) -> auto& { return o.grading.size_max; }))},
      {.name = "grading.exponent",
       .unit = "-",
       .range = open_closed(0, 10),
       .scope = kFuller,
       .doc = "Fuller curve exponent q in P(d) = (d^q - d_min^q) / (d_max^q - d_min^q); 0.5 = "
              "Fuller-Thompson, 0.45 = FHWA",
       .binding = bind(on<RandomPackOptions>([](auto& o) -> auto& { return o.grading.exponent; }))},
      {.name = "grading.sieve",
       .type = ValueType::kSieve,
       .unit = "m, %",
       .range = open_closed(0, kMaxMagnitude),
       .note = {Sentence::kSieveTableRule, {}},
       .scope = kSieve,
       .doc = "sieve table by volume, e.g. `[[0.005, 0], [0.01, 40], [0.02, 100]]`; the volume "
              "below the smallest sieve is not generated (fines)",
       .binding = bind(on<RandomPackOptions>([](auto& o) -> auto& { return o.grading.sieve; })),
       .presence = Presence::kOptional,
       .default_text = {Sentence::kDefaultNone, {}}},
  };
}

// The dense kind's fill kinds: their words are the packer kinds' words.
using Fill = decltype(DensePackOptions::fill);
constexpr auto kFillKinds = std::make_index_sequence<std::variant_size_v<Fill>>{};

template <std::size_t... I>
std::vector<std::string> fill_words(std::index_sequence<I...> /*kinds*/) {
  return {packer_kind_name(PackerOptions{std::variant_alternative_t<I, Fill>{}})...};
}

std::string fill_word(const Fill& fill) {
  return std::visit([](const auto& o) { return packer_kind_name(PackerOptions{o}); }, fill);
}

template <std::size_t... I>
Fill fill_of_word(const std::string& word, std::index_sequence<I...> /*kinds*/) {
  Fill fill;
  ((fill_word(std::variant_alternative_t<I, Fill>{}) == word
        ? (fill = std::variant_alternative_t<I, Fill>{}, 0)
        : 0),
   ...);
  return fill;
}

std::vector<PackKey> packer_keys() {
  const auto random_integer = [](const char* name, Range range, const char* doc, auto access,
                                 const char* field) {
    return PackKey{.name = name,
                   .type = ValueType::kInteger,
                   .range = range,
                   .scope = kRandom,
                   .doc = doc,
                   .binding = bind(access),
                   .fields = {field}};
  };
  return {
      {.name = "packer.kind",
       .type = ValueType::kWord,
       .words = packer_kind_names(),
       .doc = "lattice = the paper's placement (centres on a regular lattice, shapes grown in "
              "place); random = random sequential addition with a grading, random orientations, "
              "largest first; dense = a fill (`packer.fill`) compressed by hard-particle Monte "
              "Carlo, exactly overlap-free (`[densify]` keys)",
       .binding = {.get = [](const PackConfig& c) -> Value { return c.packer_name(); },
                   .set =
                       [](PackConfig& c, const Value& value) {
                         const auto& word = std::get<std::string>(value);
                         if (word != c.packer_name()) c.packer = default_packer_options(word);
                       }},
       .is_kind = true},
      {.name = "packer.fill",
       .type = ValueType::kWord,
       .words = fill_words(kFillKinds),
       .scope = {.text = "packer.kind = dense",
                 .applies =
                     [](const PackConfig& c) {
                       return std::holds_alternative<DensePackOptions>(c.packer);
                     }},
       .doc = "the packing the densifier starts from, made with that packer's keys: random "
              "(grading, target fraction, ...) or lattice",
       .binding = {.get = [](const PackConfig& c) -> Value {
                     const auto* dense = std::get_if<DensePackOptions>(&c.packer);
                     return fill_word((dense != nullptr ? *dense : DensePackOptions{}).fill);
                   },
                   .set =
                       [](PackConfig& c, const Value& value) {
                         auto* dense = std::get_if<DensePackOptions>(&c.packer);
                         const auto& word = std::get<std::string>(value);
                         if (dense != nullptr && word != fill_word(dense->fill)) {
                           dense->fill = fill_of_word(word, kFillKinds);
                         }
                       }},
       .is_kind = true},
      {.name = "packer.seed",
       .type = ValueType::kInteger,
       .range = {.lo = 0, .hi = kMaxSeed, .hi_text = "2^63 - 1"},
       .doc = "master seed; particle i draws from its own stream (seed, i), so results do not "
              "depend on the thread count. The default output name contains it. With "
              "packer.kind = dense the fill uses it and the densifier a seed derived from it "
              "(derived_densify_seed: a SplitMix64 step, so their streams differ)",
       .binding = {
           .get = [](const PackConfig& c) -> Value { return static_cast<std::int64_t>(c.seed()); },
           .set =
               [](PackConfig& c, const Value& value) {
                 set_on(on<LatticeOptions>([](auto& o) -> auto& { return o.seed; }), c, value);
                 set_on(on<RandomPackOptions>([](auto& o) -> auto& { return o.seed; }), c, value);
                 if (auto* densify = find_options<DensifyOptions>(c.packer)) {
                   densify->seed = derived_densify_seed(
                       static_cast<std::uint64_t>(std::get<std::int64_t>(value)));
                 }
               }},
       .fields = {"lattice.seed", "random.seed"}},
      {.name = "packer.threads",
       .type = ValueType::kInteger,
       .range = closed(0, 4096),
       .written = kNever,
       .doc = "worker threads, 0 = all cores; results do not depend on it (not stored in the "
              "file)",
       .binding = members<PackConfig>([](auto& c) -> auto& { return c.threads; })},
      {.name = "packer.gap",
       .unit = "m",
       .range = closed(0, kMaxMagnitude),
       .doc = "minimum distance between particles",
       .binding = bind(on<LatticeOptions>([](auto& o) -> auto& { return o.gap; }),
                       on<RandomPackOptions>([](auto& o) -> auto& { return o.gap; })),
       .fields = {"lattice.gap", "random.gap"}},
      {.name = "packer.spacing",
       .unit = "m",
       .range = closed(0, kMaxMagnitude),
       .note = {Sentence::kZeroOrAtLeast, {"particle.radius"}},
       .scope = kLattice,
       .doc = "centre-to-centre lattice spacing. 0 = 2 R + gap (particles cannot touch and grow "
              "independently); smaller values pack sites closer and turn on the paper's contact "
              "check (growth toward a neighbour is stopped, and a particle that still touches is "
              "shrunk about its centre)",
       .binding = bind(on<LatticeOptions>([](auto& o) -> auto& { return o.spacing; })),
       .fields = {"lattice.spacing"}},
      {.name = "packer.target_count",
       .type = ValueType::kInteger,
       .range = closed(1, 1e8),
       .scope = kRandom,
       .written = kCountTarget,
       .doc = "place this many particles (instead of `target_fraction`). Refused when their "
              "estimated solid volume exceeds 0.74 of the container, or the run's memory "
              "estimate the memory limit (docs/packing.md)",
       .binding = {
           .get = [](const PackConfig& c) -> Value {
             const RandomPackOptions* random = random_of(c);
             return static_cast<std::int64_t>(
                 (random != nullptr ? *random : default_options<RandomPackOptions>()).count);
           },
           .set =
               [](PackConfig& c, const Value& value) {
                 auto* random = find_options<RandomPackOptions>(c.packer);
                 if (random == nullptr) return;
                 random->count = static_cast<std::uint64_t>(std::get<std::int64_t>(value));
                 random->target = PackTarget::kCount;
               }},
       .presence = Presence::kOptional,
       .default_text = {Sentence::kDefaultUnset, {}},
       .excludes = "packer.target_fraction",
       .fields = {"random.count"}},
      {.name = "packer.target_fraction",
       .unit = "-",
       .range = open_closed(0, 0.9),
       .scope = kRandom,
       .written = kFractionTarget,
       .doc = "place particles until solid volume / container volume reaches this (the default "
              "target). packer.kind = dense, densify.mode = fixed: the fill's fraction in the "
              "enlarged container, below `densify.target_fraction`",
       .binding = bind(on<RandomPackOptions>([](auto& o) -> auto& { return o.volume_fraction; })),
       .fields = {"random.volume_fraction"}},
      random_integer(
          "packer.attempts", closed(1, 1e9), "candidate poses per particle before it is skipped",
          on<RandomPackOptions>([](auto& o) -> auto& { return o.max_attempts_per_particle; }),
          "random.max_attempts_per_particle"),
      random_integer("packer.max_total_attempts", closed(1, 1e12),
                     "candidate poses for the whole run; the run stops when they are used up",
                     on<RandomPackOptions>([](auto& o) -> auto& { return o.max_total_attempts; }),
                     "random.max_total_attempts"),
      random_integer(
          "packer.max_consecutive_failures", closed(1, 1e9),
          "stop when this many particles in a row could not be placed (the packing is jammed)",
          on<RandomPackOptions>([](auto& o) -> auto& { return o.max_consecutive_failures; }),
          "random.max_consecutive_failures"),
      random_integer(
          "packer.shape_library", closed(0, 1e6),
          "0 = a unique shape per particle; K > 0 = K unit-size shapes grown once and reused, "
          "scaled and randomly rotated (for ~10^6 particles; needs `particle.edge_length = 0`)",
          on<RandomPackOptions>([](auto& o) -> auto& { return o.shape.library_size; }),
          "shape.library_size"),
  };
}

// One key per output format (the writer puts them in name order: [output] is a family table).
std::vector<PackKey> output_keys() {
  std::vector<PackKey> keys;
  for (const auto& format : output_format_names()) {
    keys.push_back(
        {.name = "output." + format,
         .type = ValueType::kPath,
         .written = {.text = "given",
                     .applies =
                         [format](const PackConfig& c) { return c.outputs.count(format) > 0; }},
         .doc = format == "native"
                    ? "the .h5 file `aggpack pack` writes when `-o` is not given"
                    : "a " + format +
                          " file `aggpack pack` writes right after the native file, with the "
                          "exporter's defaults (other options: `aggpack export`)",
         .binding = {.get = [format](const PackConfig& c) -> Value {
                       const auto found = c.outputs.find(format);
                       return found == c.outputs.end() ? std::string() : found->second;
                     },
                     .set =
                         [format](PackConfig& c, const Value& value) {
                           c.outputs[format] = std::get<std::string>(value);
                         }},
         .presence = Presence::kOptional,
         .default_text = {Sentence::kDefaultNone, {}}});
  }
  return keys;
}

}  // namespace

const Schema<PackConfig>& pack_schema() {
  static const Schema<PackConfig> schema = [] {
    Schema<PackConfig> s;
    s.tables = {{.name = "container"}, {.name = "particle"},
                {.name = "grading"},   {.name = "packer"},
                {.name = "densify"},   {.name = "output", .member_word = "output format"}};
    for (auto part : {container_keys(), particle_keys(), config_detail::library_keys(),
                      grading_keys(), packer_keys(), densify_keys(), output_keys()}) {
      for (auto& key : part) s.keys.push_back(std::move(key));
    }
    config_detail::fill_defaults(s, PackConfig{});
    return s;
  }();
  return schema;
}

std::string pack_keys_markdown(const std::string& table) {
  return markdown_table(pack_schema(), table);
}

}  // namespace aggpack
