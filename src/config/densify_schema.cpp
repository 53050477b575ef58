// The [densify] keys of the "dense" packer kind, declared once (see aggpack/config/schema.h):
// the densifier's options (DensifyOptions, aggpack/pack/dense_packer.h), defaults from the
// struct. packer.seed seeds the densifier (derived_densify_seed), packer.gap is the default of
// densify.gap; the fill is set by the packer keys (packer.fill).

#include <numbers>
#include <utility>

#include "pack_binding.h"

namespace aggpack::config_detail {

namespace {

using PackKey = Key<PackConfig>;
using PackScope = Scope<PackConfig>;

const DensifyOptions* densify_of(const PackConfig& c) {
  return find_options<DensifyOptions>(c.packer);
}
bool is_dense(const PackConfig& c) { return densify_of(c) != nullptr; }

const PackScope kDense{.text = "packer.kind = dense", .applies = is_dense};
const PackScope kFixedMode{.text = "dense with densify.mode = fixed",
                           .applies = [](const PackConfig& c) {
                             return is_dense(c) && densify_of(c)->mode == DensifyMode::kFixed;
                           }};
const PackScope kBedMode{.text = "dense with densify.mode = bed",
                         .applies = [](const PackConfig& c) {
                           return is_dense(c) && densify_of(c)->mode == DensifyMode::kBed;
                         }};

}  // namespace

// The densifier's options (packer.kind = dense); packer.seed seeds it (derived), packer.gap is
// the default of densify.gap.
std::vector<PackKey> densify_keys() {
  const auto key = [](const char* name, ValueType type, const char* unit, Range range,
                      const PackScope& scope, const char* doc, auto access) {
    return PackKey{.name = name,
                   .type = type,
                   .unit = unit,
                   .range = range,
                   .scope = scope,
                   .doc = doc,
                   .binding = bind(on<DensifyOptions>(access))};
  };
  constexpr auto kFloat = ValueType::kFloat;
  constexpr auto kInteger = ValueType::kInteger;
  std::vector<PackKey> keys;
  keys.push_back(
      {.name = "densify.mode",
       .type = ValueType::kWord,
       .words = {to_string(DensifyMode::kFixed), to_string(DensifyMode::kBed)},
       .scope = kDense,
       .doc = "fixed = end in the given container at `densify.target_fraction`: the random fill "
              "runs in the container enlarged by (densify.target_fraction / "
              "packer.target_fraction)^(1/3) in every extent and is compressed into the given one "
              "(positions only; shapes are never deformed); bed = a gravity bed in the given "
              "container: moves biased downward until the bed stops sinking",
       .binding = {.get = [](const PackConfig& c) -> Value {
                     const DensifyOptions* d = densify_of(c);
                     return to_string((d != nullptr ? *d : default_options<DensifyOptions>()).mode);
                   },
                   .set =
                       [](PackConfig& c, const Value& value) {
                         if (auto* d = find_options<DensifyOptions>(c.packer)) {
                           d->mode =
                               parse_densify_mode("densify.mode", std::get<std::string>(value));
                         }
                       }}});
  keys.push_back(key(
      "densify.target_fraction", kFloat, "-", {.lo = 0, .hi = 0.95, .hi_end = End::kOpen},
      kFixedMode,
      "solid fraction to reach in the given container (> packer.target_fraction, the fill's; "
      "needs packer.fill = random); 0 = no compression (the fill is only shaken). The run "
      "stops there, or earlier when jammed or out of budget (then the container is larger); a "
      "fill that jams below its target gives a lower fraction; both are reported",
      [](auto& o) -> auto& { return o.target_fraction; }));
  PackKey gap = key(
      "densify.gap", kFloat, "m", closed(0, kMaxMagnitude), kDense,
      "minimum particle distance kept while densifying", [](auto& o) -> auto& { return o.gap; });
  gap.note = {Sentence::kAtMost, {"packer.gap"}};
  gap.default_from = "packer.gap";
  keys.push_back(std::move(gap));
  keys.push_back(key(
      "densify.max_sweeps", kInteger, "", closed(1, 1e9), kDense,
      "sweep budget (one trial move per particle each); the run stops there and "
      "keeps what it reached",
      [](auto& o) -> auto& { return o.max_sweeps; }));
  keys.push_back(key(
      "densify.max_seconds", kFloat, "s", closed(0, kMaxMagnitude), kDense,
      "wall-time budget, 0 = none. A run stopped by time is not reproducible "
      "(sweep budgets are)",
      [](auto& o) -> auto& { return o.max_seconds; }));
  keys.push_back(key(
      "densify.stall_sweeps", kInteger, "", closed(1, 1e9), kDense,
      "stall window: fixed stops as jammed when the fraction gained less than "
      "`stall_tolerance` over it; bed stops as settled when the mean height sank "
      "less than `stall_tolerance` mean bounding radii",
      [](auto& o) -> auto& { return o.stall_sweeps; }));
  keys.push_back(key(
      "densify.stall_tolerance", kFloat, "-", closed(0, kMaxMagnitude), kDense,
      "see `stall_sweeps` (a fraction for fixed, bounding radii for bed)",
      [](auto& o) -> auto& { return o.stall_tolerance; }));
  keys.push_back(key(
      "densify.compress_interval", kInteger, "", closed(1, 1000), kFixedMode,
      "squeeze the container only on sweeps whose number is a multiple of this",
      [](auto& o) -> auto& { return o.compress_interval; }));
  keys.push_back(key(
      "densify.max_compression", kFloat, "-", open_closed(0, 0.1), kDense,
      "fixed: largest relative shrink of any container extent in one squeeze (the step adapts "
      "below it); both modes size the cell grid for it",
      [](auto& o) -> auto& { return o.max_compression; }));
  keys.push_back(key(
      "densify.bed_temperature", kFloat, "-", closed(0, kMaxMagnitude), kBedMode,
      "initial temperature: a particle of mean volume rising one mean bounding "
      "radius is accepted with probability exp(-1 / T); 0 = never rise",
      [](auto& o) -> auto& { return o.bed_temperature; }));
  keys.push_back(key(
      "densify.bed_cooling", kFloat, "-", open_closed(0, 1), kBedMode,
      "temperature factor per sweep", [](auto& o) -> auto& { return o.bed_cooling; }));
  keys.push_back(key(
      "densify.target_acceptance", kFloat, "-",
      {.lo = 0, .hi = 1, .lo_end = End::kOpen, .hi_end = End::kOpen}, kDense,
      "acceptance rate the step sizes adapt to",
      [](auto& o) -> auto& { return o.target_acceptance; }));
  keys.push_back(key(
      "densify.translation_step", kFloat, "-", open_closed(0, 1), kDense,
      "initial translation step, in bounding radii",
      [](auto& o) -> auto& { return o.translation_step; }));
  keys.push_back(key(
      "densify.rotation_step", kFloat, "rad",
      {.lo = 0, .hi = std::numbers::pi, .lo_end = End::kOpen, .hi_text = "pi"}, kDense,
      "initial rotation step", [](auto& o) -> auto& { return o.rotation_step; }));
  keys.push_back(key(
      "densify.rotation_probability", kFloat, "-", closed(0, 1), kDense,
      "share of trial moves that rotate (the others translate)",
      [](auto& o) -> auto& { return o.rotation_probability; }));
  return keys;
}

}  // namespace aggpack::config_detail
