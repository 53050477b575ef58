// Every key of the pack configuration, declared once (see aggpack/config/schema.h). A new key is
// one entry here: its binding names the options member it sets, whose default is the key's.
// Container keys come from container_kinds(), output keys from output_format_names().

#include "aggpack/config/config.h"
#include "aggpack/io/export.h"
#include "aggpack/pack/container.h"
#include "binding.h"

namespace aggpack {

namespace {

using config_detail::members;
using PackKey = Key<PackConfig>;
using PackScope = Scope<PackConfig>;

constexpr double kHuge = 1e6;  // 1000 km: any larger length is a unit mistake
constexpr double kMaxSeed = 9223372036854775807.0;

bool is_random(const PackConfig& c) { return c.packer == PackerKind::kRandom; }
bool has_grading(const PackConfig& c, GradingKind kind) {
  return is_random(c) && c.random.grading.kind == kind;
}

const PackScope kAlways{};
const PackScope kNever{.text = "never", .applies = [](const PackConfig&) { return false; }};
const PackScope kLattice{.text = "packer.kind = lattice",
                         .applies = [](const PackConfig& c) { return !is_random(c); }};
const PackScope kRandom{.text = "packer.kind = random", .applies = is_random};
const PackScope kLatticeOrUniform{
    .text = "lattice, or random with grading.kind = uniform", .applies = [](const PackConfig& c) {
      return !is_random(c) || c.random.grading.kind == GradingKind::kUniform;
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
const PackScope kRelativeEdge{
    .text = "random with particle.edge_length = 0",
    .applies = [](const PackConfig& c) { return is_random(c) && c.random.shape.edge_length == 0; }};
const PackScope kCountTarget{.text = "random with packer.target_count",
                             .applies = [](const PackConfig& c) {
                               return is_random(c) && c.random.target == PackTarget::kCount;
                             }};
const PackScope kFractionTarget{
    .text = "random without packer.target_count", .applies = [](const PackConfig& c) {
      return is_random(c) && c.random.target == PackTarget::kVolumeFraction;
    }};

// Both packers' containers.
template <typename Set>
void on_containers(PackConfig& c, Set set) {
  set(c.lattice.container);
  set(c.random.container);
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
           .range = open_closed(0, kHuge),
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
  keys.push_back({.name = "container.wall_gap",
                  .unit = "m",
                  .range = closed(0, kHuge),
                  .note = "< half the smallest extent",
                  .doc = "minimum distance from every particle to every wall",
                  .binding = members<PackConfig>(
                      [](auto& c) -> auto& { return c.lattice.container.wall_gap; },
                      [](auto& c) -> auto& { return c.random.container.wall_gap; })});
  return keys;
}

std::vector<PackKey> particle_keys() {
  return {
      {.name = "particle.alpha",
       .unit = "-",
       .range = closed(0, 1),
       .doc = "the paper's Eq. 3 shape control: 1 = regular, full shapes (octahedron-like); 0 = "
              "sharp, flat shapes",
       .binding = members<PackConfig>(
           [](auto& c) -> auto& { return c.lattice.alpha; },
           [](auto& c) -> auto& { return c.random.shape.alpha; }),
       .fields = {"lattice.alpha", "shape.alpha"}},
      {.name = "particle.radius",
       .unit = "m",
       .range = open_closed(0, kHuge),
       .scope = kLatticeOrUniform,
       .written = kLattice,
       .doc = "control radius R of every lattice particle; for the random packer the default of "
              "`radius_min` and `radius_max`",
       .binding = members<PackConfig>([](auto& c) -> auto& { return c.lattice.radius; }),
       .fields = {"lattice.radius"}},
      {.name = "particle.radius_min",
       .unit = "m",
       .range = open_closed(0, kHuge),
       .note = "<= radius_max",
       .scope = kUniform,
       .doc = "smallest control radius of the uniform grading (uniform by number)",
       .binding = members<PackConfig>([](auto& c) -> auto& { return c.random.grading.radius_min; }),
       .default_from = "particle.radius",
       .fields = {"grading.radius_min"}},
      {.name = "particle.radius_max",
       .unit = "m",
       .range = open_closed(0, kHuge),
       .note = ">= radius_min",
       .scope = kUniform,
       .doc = "largest control radius of the uniform grading",
       .binding = members<PackConfig>([](auto& c) -> auto& { return c.random.grading.radius_max; }),
       .default_from = "particle.radius",
       .fields = {"grading.radius_max"}},
      {.name = "particle.edge_length",
       .unit = "m",
       .range = closed(0, kHuge),
       .note = "0 only with packer.kind = random",
       .doc = "growth edge-length control L: a particle grows on its longest edge until every "
              "edge is <= L. 0 = relative: L = `edge_length_ratio` x r for each particle (the "
              "same shape statistics at every size)",
       .binding = members<PackConfig>(
           [](auto& c) -> auto& { return c.lattice.edge_length; },
           [](auto& c) -> auto& { return c.random.shape.edge_length; }),
       .fields = {"lattice.edge_length", "shape.edge_length", "edge_length"}},
      {.name = "particle.edge_length_ratio",
       .unit = "-",
       .range = closed(0.05, 10),
       .scope = kRelativeEdge,
       .doc = "L / r for each particle when particle.edge_length = 0",
       .binding =
           members<PackConfig>([](auto& c) -> auto& { return c.random.shape.edge_length_ratio; }),
       .fields = {"shape.edge_length_ratio"}},
      {.name = "particle.max_vertices",
       .type = ValueType::kInteger,
       .range = closed(6, 1e6),
       .doc = "vertex cap per particle; an L too small for the radius is rejected up front "
              "(LimitExceeded)",
       .binding = members<PackConfig>(
           [](auto& c) -> auto& { return c.lattice.max_vertices; },
           [](auto& c) -> auto& { return c.random.shape.max_vertices; }),
       .fields = {"lattice.max_vertices", "shape.max_vertices", "max_vertices"}},
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
           .get = [](const PackConfig& c) -> Value { return to_string(c.random.grading.kind); },
           .set =
               [](PackConfig& c, const Value& value) {
                 for (const auto kind :
                      {GradingKind::kUniform, GradingKind::kFuller, GradingKind::kSieve}) {
                   if (to_string(kind) == std::get<std::string>(value)) {
                     c.random.grading.kind = kind;
                   }
                 }
               }}},
      {.name = "grading.size_min",
       .unit = "m",
       .range = open_closed(0, kHuge),
       .note = "< size_max",
       .scope = kFuller,
       .doc = "Fuller curve: smallest control diameter d_min",
       .binding = members<PackConfig>([](auto& c) -> auto& { return c.random.grading.size_min; })},
      {.name = "grading.size_max",
       .unit = "m",
       .range = open_closed(0, kHuge),
       .note = "> size_min",
       .scope = kFuller,
       .doc = "Fuller curve: largest control diameter d_max",
       .binding = members<PackConfig>([](auto& c) -> auto& { return c.random.grading.size_max; })},
      {.name = "grading.exponent",
       .unit = "-",
       .range = open_closed(0, 10),
       .scope = kFuller,
       .doc = "Fuller curve exponent q in P(d) = (d^q - d_min^q) / (d_max^q - d_min^q); 0.5 = "
              "Fuller-Thompson, 0.45 = FHWA",
       .binding = members<PackConfig>([](auto& c) -> auto& { return c.random.grading.exponent; })},
      {.name = "grading.sieve",
       .type = ValueType::kSieve,
       .unit = "m, %",
       .range = open_closed(0, kHuge),
       .note = ">= 2 rows [size, percent passing]; sizes increasing, percents [0, 100] "
               "non-decreasing, last 100",
       .scope = kSieve,
       .doc = "sieve table by volume, e.g. `[[0.005, 0], [0.01, 40], [0.02, 100]]`; the volume "
              "below the smallest sieve is not generated (fines)",
       .binding = members<PackConfig>([](auto& c) -> auto& { return c.random.grading.sieve; }),
       .presence = Presence::kOptional,
       .default_text = "(none)"},
  };
}

std::vector<PackKey> packer_keys() {
  const auto random_integer = [](const char* name, Range range, const char* doc, auto access,
                                 const char* field) {
    return PackKey{.name = name,
                   .type = ValueType::kInteger,
                   .range = range,
                   .scope = kRandom,
                   .doc = doc,
                   .binding = members<PackConfig>(access),
                   .fields = {field}};
  };
  return {
      {.name = "packer.kind",
       .type = ValueType::kWord,
       .words = {"lattice", "random"},
       .doc = "lattice = the paper's placement (centres on a regular lattice, shapes grown in "
              "place); random = random sequential addition with a grading, random orientations, "
              "largest first",
       .binding = {.get = [](const PackConfig& c) -> Value { return c.packer_name(); },
                   .set =
                       [](PackConfig& c, const Value& value) {
                         c.packer = std::get<std::string>(value) == "random" ? PackerKind::kRandom
                                                                             : PackerKind::kLattice;
                       }}},
      {.name = "packer.seed",
       .type = ValueType::kInteger,
       .range = {.lo = 0, .hi = kMaxSeed, .hi_text = "2^63 - 1"},
       .doc = "master seed; particle i draws from its own stream (seed, i), so results do not "
              "depend on the thread count. The default output name contains it",
       .binding = members<PackConfig>(
           [](auto& c) -> auto& { return c.lattice.seed; },
           [](auto& c) -> auto& { return c.random.seed; }),
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
       .range = closed(0, kHuge),
       .doc = "minimum distance between particles",
       .binding = members<PackConfig>(
           [](auto& c) -> auto& { return c.lattice.gap; },
           [](auto& c) -> auto& { return c.random.gap; }),
       .fields = {"lattice.gap", "random.gap"}},
      {.name = "packer.spacing",
       .unit = "m",
       .range = closed(0, kHuge),
       .note = "0 or >= particle.radius",
       .scope = kLattice,
       .doc = "centre-to-centre lattice spacing. 0 = 2 R + gap (particles cannot touch and grow "
              "independently); smaller values pack sites closer and turn on the paper's contact "
              "check (growth toward a neighbour is stopped, and a particle that still touches is "
              "shrunk about its centre)",
       .binding = members<PackConfig>([](auto& c) -> auto& { return c.lattice.spacing; }),
       .fields = {"lattice.spacing"}},
      {.name = "packer.target_count",
       .type = ValueType::kInteger,
       .range = closed(1, 1e8),
       .scope = kRandom,
       .written = kCountTarget,
       .doc = "place this many particles (instead of `target_fraction`). Refused when their "
              "estimated solid volume exceeds 0.74 of the container, or the run's memory "
              "estimate the memory limit (README, \"Runs that cannot work\")",
       .binding = {.get = [](const PackConfig& c) -> Value {
                     return static_cast<std::int64_t>(c.random.count);
                   },
                   .set =
                       [](PackConfig& c, const Value& value) {
                         c.random.count = static_cast<std::uint64_t>(std::get<std::int64_t>(value));
                         c.random.target = PackTarget::kCount;
                       }},
       .presence = Presence::kOptional,
       .default_text = "(unset)",
       .excludes = "packer.target_fraction",
       .fields = {"random.count"}},
      {.name = "packer.target_fraction",
       .unit = "-",
       .range = open_closed(0, 0.9),
       .scope = kRandom,
       .written = kFractionTarget,
       .doc = "place particles until solid volume / container volume reaches this (the default "
              "target)",
       .binding = members<PackConfig>([](auto& c) -> auto& { return c.random.volume_fraction; }),
       .fields = {"random.volume_fraction"}},
      random_integer(
          "packer.attempts", closed(1, 1e9), "candidate poses per particle before it is skipped",
          [](auto& c) -> auto& { return c.random.max_attempts_per_particle; },
          "random.max_attempts_per_particle"),
      random_integer(
          "packer.max_total_attempts", closed(1, 1e12),
          "candidate poses for the whole run; the run stops when they are used up",
          [](auto& c) -> auto& { return c.random.max_total_attempts; },
          "random.max_total_attempts"),
      random_integer(
          "packer.max_consecutive_failures", closed(1, 1e9),
          "stop when this many particles in a row could not be placed (the packing is jammed)",
          [](auto& c) -> auto& { return c.random.max_consecutive_failures; },
          "random.max_consecutive_failures"),
      random_integer(
          "packer.shape_library", closed(0, 1e6),
          "0 = a unique shape per particle; K > 0 = K unit-size shapes grown once and reused, "
          "scaled and randomly rotated (for ~10^6 particles; needs `particle.edge_length = 0`)",
          [](auto& c) -> auto& { return c.random.shape.library_size; }, "shape.library_size"),
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
         .default_text = "(none)"});
  }
  return keys;
}

}  // namespace

const Schema<PackConfig>& pack_schema() {
  static const Schema<PackConfig> schema = [] {
    Schema<PackConfig> s;
    s.tables = {{.name = "container"},
                {.name = "particle"},
                {.name = "grading"},
                {.name = "packer"},
                {.name = "output", .member_word = "output format"}};
    for (auto part :
         {container_keys(), particle_keys(), grading_keys(), packer_keys(), output_keys()}) {
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
