#include "aggpack/pack/resources.h"

#include <sys/resource.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "aggpack/core/error.h"
#include "aggpack/core/parallel.h"
#include "aggpack/core/rng.h"
#include "aggpack/geom/mass_properties.h"
#include "aggpack/pack/grading.h"
#include "aggpack/pack/packing.h"
#include "aggpack/shape/generator.h"

namespace aggpack {

namespace {

constexpr double kMemoryShare = 0.8;       // of the machine's (or cgroup's) memory
constexpr double kSampleVertices = 20000;  // grown vertices the sample may cost at most
constexpr int kMaxSample = 64;
constexpr std::uint64_t kSampleSalt = 0x73616D706C65ULL;  // library sample streams
// Bookkeeping per particle besides its shape's vertices and triangles, measured on the structs of
// src/pack/random_packer.cpp (size-list item and stored shape, both in doubling vectors; order;
// pose; grid entry; output Particle) and src/pack/lattice_packer.cpp (grown body, site, index).
constexpr double kRandomBytesPerItem = 640.0;
constexpr double kRandomLibraryBytesPerItem = 450.0;
constexpr double kLatticeBytesPerSite = 300.0;
// A rough placement cost per particle (grid look-up and exact overlap tests), for the time
// estimate of heavy_run_note only: bench/RESULTS.md, "Packing", a million particles placed in 47 s.
constexpr double kPlacementSecondsPerParticle = 5e-5;
// densify (bench/RESULTS.md, "Densifying packer"): CPU seconds per particle and sweep (9,078
// particles: 3.4e-6; 101,303: 8.0e-6) and peak memory per particle (101,303: 530 MB, 5.2 kB).
constexpr double kDensifySecondsPerParticleSweep = 5e-6;
constexpr double kDensifyBytesPerParticle = 5.2e3;
// Bullet (bench/RESULTS.md, "Steps per second"): CPU seconds per particle and step, 5.7e-5 at
// 1,000 particles and 1.5e-4 at 10,000 (a power law between, flat below 1,000). Memory per body
// besides its shape's vertices (rigid body, convex hull shape, broadphase proxy, contact
// manifolds): an allowance, not measured.
constexpr double kSimSecondsPerBodyStep = 5.7e-5;
constexpr double kSimCostExponent = 0.42;  // log10(1.5e-4 / 5.7e-5)
constexpr double kSimBytesPerBody = 4e3;
// mesomodel (bench/RESULTS.md, "Concrete mesomodel mesh"): wall seconds and peak bytes per
// aggregate (5,962: 15.2 s, 1.17 GB; 23,968: 66.9 s, 4.44 GB); the phase image: 5 bytes and
// ~0.8 microseconds per voxel (256^3 in 13.7 s).
constexpr double kMeshSecondsPerAggregate = 2.8e-3;
constexpr double kMeshBytesPerAggregate = 1.9e5;
constexpr double kVoxelBytes = 5.0;
constexpr double kVoxelSeconds = 8e-7;
constexpr double kGravity = 9.81;
// export (bench/RESULTS.md, "Exports", idle machine): 100,000 paper particles, 3.65 M cells;
// C3D4 .inp 301 MB in 1.17 s, C3D10 998 MB in 5.10 s (ASCII STL alike: 999 MB). TetGen: the
// paper's 1,050 shapes in 1.1 s with -j 1, the whole export included (2026-12-05, loaded VM).
constexpr double kExportBytesPerCell = 85.0;
constexpr double kExportWideBytesPerCell = 275.0;
constexpr double kExportSecondsPerCell = 3.2e-7;
constexpr double kExportWideSecondsPerCell = 1.4e-6;
constexpr double kTetGenSecondsPerShape = 1e-3;
constexpr double kTetGenBytesPerElement = 40.0;  // 4 node numbers, face flags, ~0.5 node
// render (bench/RESULTS.md, "Rendering", loaded VM): 1,050 particles 1.65 s, 100,000 9.05 s.
constexpr double kRenderSetupSeconds = 1.5;
constexpr double kRenderSecondsPerParticle = 8e-5;
constexpr double kRenderBytesPerParticle = 200.0;  // pose, colour, draw lists, per-instance data
// shapes -n: a chunk of 8,192 descriptor rows in memory (app/cli/shape_commands.cpp); a CSV row of
// ~13 numbers of 17 digits.
constexpr double kShapesChunk = 8192.0;
constexpr double kShapesBytesPerRow = 300.0;
// A shape library may hold this many times the particles a target needs (and at least
// kLibraryFloor shapes): beyond that most shapes are grown and never used.
constexpr double kLibraryHeadroom = 10.0;
constexpr double kLibraryFloor = 1000.0;

// "2G", "512M", "1000000" -> bytes; negative when it is not a size.
double parse_size(const std::string& text) {
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (end == text.c_str() || !std::isfinite(value) || value <= 0.0) return -1.0;
  const std::string suffix(end);
  double factor = 1.0;
  if (suffix == "K" || suffix == "k")
    factor = 1024.0;
  else if (suffix == "M" || suffix == "m")
    factor = 1024.0 * 1024.0;
  else if (suffix == "G" || suffix == "g")
    factor = 1024.0 * 1024.0 * 1024.0;
  else if (suffix == "T" || suffix == "t")
    factor = 1024.0 * 1024.0 * 1024.0 * 1024.0;
  else if (!suffix.empty())
    return -1.0;
  return value * factor;
}

// A cgroup memory limit file: a number of bytes, or "max" / a huge value for none.
double cgroup_limit(const char* path) {
  std::ifstream in(path);
  std::string text;
  if (!(in >> text) || text == "max") return std::numeric_limits<double>::infinity();
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  return end != text.c_str() && value > 0.0 ? value : std::numeric_limits<double>::infinity();
}

struct ShapeSample {
  double volume_ratio = 0.0;       // sum of volumes / sum of control-sphere volumes
  double mean_bytes = 0.0;         // heap bytes per shape
  double seconds_per_shape = 0.0;  // CPU time to grow one (not reproducible; estimates only)
};

// This thread's CPU time: the sample's cost whatever else the machine runs (a loaded machine
// would otherwise announce every small run as heavy).
double thread_cpu_seconds() {
  timespec now{};
  ::clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

// Wall time of growing `shapes` shapes on the allowed threads and placing `particles`.
double run_seconds(const ShapeSample& sample, double shapes, double particles) {
  return shapes * sample.seconds_per_shape / std::max(1, allowed_threads()) +
         particles * kPlacementSecondsPerParticle;
}

// How many shapes of about `vertices` vertices the sample may grow.
int sample_size_for(double vertices, std::uint64_t available) {
  const double fit = std::floor(kSampleVertices / std::max(vertices, 6.0));
  return static_cast<int>(
      std::clamp<double>(std::min<double>(fit, static_cast<double>(available)), 1.0, kMaxSample));
}

ShapeSample sample_shapes(
    int count, const std::function<std::pair<ConvexPolyhedron, double>(std::uint64_t)>& grow) {
  ShapeSample sample;
  double volume = 0.0;
  double sphere = 0.0;
  double bytes = 0.0;
  const double start = thread_cpu_seconds();
  for (int i = 0; i < count; ++i) {
    const auto [body, radius] = grow(static_cast<std::uint64_t>(i));
    volume += mass_properties(body).volume;
    sphere += 4.0 / 3.0 * std::numbers::pi * radius * radius * radius;
    bytes += heap_bytes(body);
  }
  sample.volume_ratio = sphere > 0.0 ? volume / sphere : 0.0;
  sample.mean_bytes = bytes / count;
  sample.seconds_per_shape = (thread_cpu_seconds() - start) / count;
  return sample;
}

std::string count_text(double value) {
  char buffer[64];
  if (value < 1e6) {
    std::snprintf(buffer, sizeof buffer, "%.0f", value);
  } else {
    std::snprintf(buffer, sizeof buffer, "%.2g", value);
  }
  return buffer;
}

std::string volume_text(double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.3g", value);
  return buffer;
}

// "a run that fits in memory: ... (SOURCE); ADVICE" (advice: a Sentence::kPhrase* word).
Wording memory_advice(const RunEstimate& estimate, const MemoryLimit& limit,
                      const std::string& advice) {
  const std::string variable = "AGGPACK_MEMORY_LIMIT";
  std::vector<std::string> values = {count_text(estimate.particles),
                                     format_bytes(estimate.bytes_per_particle),
                                     format_bytes(estimate.bytes), format_bytes(limit.bytes)};
  if (!limit.set_text.empty()) {
    values.insert(values.end(), {variable, limit.set_text, advice});
    return {Sentence::kMemoryRunSet, values};
  }
  values.insert(values.end(), {limit.share_of, limit.share_bytes, variable, advice});
  return {Sentence::kMemoryRunShare, values};
}

}  // namespace

MemoryLimit memory_limit() {
  MemoryLimit limit;
  if (const char* text = std::getenv("AGGPACK_MEMORY_LIMIT"); text != nullptr) {
    limit.bytes = parse_size(text);
    if (!(limit.bytes > 0.0)) {
      throw InvalidInput("AGGPACK_MEMORY_LIMIT", std::string(text).substr(0, 40),
                         Wording{Sentence::kMemorySize, {}});
    }
    limit.source = "AGGPACK_MEMORY_LIMIT=" + std::string(text);
    limit.set_text = text;
    return limit;
  }
  double bytes =
      static_cast<double>(sysconf(_SC_PHYS_PAGES)) * static_cast<double>(sysconf(_SC_PAGESIZE));
  std::string what = english_words(Sentence::kPhrasePhysicalMemory);
  if (!(bytes > 0.0)) bytes = std::numeric_limits<double>::infinity();
  for (const char* path :
       {"/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory/memory.limit_in_bytes"}) {
    const double value = cgroup_limit(path);
    if (value < bytes) {
      bytes = value;
      what = english_words(Sentence::kPhraseCgroupMemory);
    }
  }
  rlimit address_space{};
  if (getrlimit(RLIMIT_AS, &address_space) == 0 && address_space.rlim_cur != RLIM_INFINITY &&
      static_cast<double>(address_space.rlim_cur) < bytes) {
    bytes = static_cast<double>(address_space.rlim_cur);
    what = english_words(Sentence::kPhraseAddressSpace);
  }
  if (!std::isfinite(bytes)) bytes = 1e15;
  limit.bytes = kMemoryShare * bytes;
  limit.source =
      "80% of " + what + " " + format_bytes(bytes) + "; AGGPACK_MEMORY_LIMIT overrides it";
  limit.share_of = what;
  limit.share_bytes = format_bytes(bytes);
  return limit;
}

double heap_bytes(const ConvexPolyhedron& body) {
  constexpr double kAllocation = 16.0;  // malloc header per block
  return static_cast<double>(body.vertex_count() * sizeof(Vec3) +
                             body.triangle_count() * sizeof(Triangle)) +
         2.0 * kAllocation;
}

std::string format_bytes(double bytes) {
  static const char* const units[] = {"B", "kB", "MB", "GB", "TB", "PB", "EB"};
  int unit = 0;
  while (bytes >= 1000.0 && unit < 6) {
    bytes /= 1000.0;
    ++unit;
  }
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, unit == 0 ? "%.0f %s" : "%.3g %s", bytes, units[unit]);
  return buffer;
}

RunEstimate estimate_run(const RandomPackOptions& options) {
  const ShapeOptions& shape = options.shape;
  // A file library (particle.library) is sampled from its loaded shapes, not grown.
  const ShapeLibrary* files = shape.files.loaded.get();
  const std::uint64_t library_count = files != nullptr ? files->shapes.size() : shape.library_size;
  const bool is_library = library_count > 0;
  const double largest_radius = largest_size(options.grading) / 2.0;
  const double largest_edge =
      shape.edge_length > 0.0 ? shape.edge_length : shape.edge_length_ratio * largest_radius;
  const int count =
      sample_size_for(estimated_vertex_count(largest_radius, largest_edge, shape.form.growth),
                      is_library ? library_count : std::numeric_limits<std::uint64_t>::max());
  ShapeSample sample;
  if (files != nullptr) {
    sample = sample_shapes(
        count, [&](std::uint64_t k) { return std::make_pair(files->shapes[k].body, 1.0); });
  } else if (is_library) {
    sample = sample_shapes(count, [&](std::uint64_t k) {
      Rng rng(options.seed ^ kSampleSalt, k);
      return std::make_pair(grow_aggregate(growth_params(shape, 1.0), rng), 1.0);
    });
  } else {
    // The run's own first draws: size from stream (seed, i), then the shape from the same stream.
    sample = sample_shapes(count, [&](std::uint64_t i) {
      Rng rng(options.seed, i);
      const double radius = sample_size(options.grading, rng.uniform()) / 2.0;
      return std::make_pair(grow_aggregate(growth_params(shape, radius), rng), radius);
    });
  }
  RunEstimate estimate;
  const double container_volume = options.container.volume();
  estimate.mean_volume =
      sample.volume_ratio * std::numbers::pi / 6.0 * mean_cubed_size(options.grading);
  estimate.particles = options.target == PackTarget::kCount
                           ? static_cast<double>(options.count)
                           : options.volume_fraction * container_volume / estimate.mean_volume;
  estimate.solid_fraction = estimate.particles * estimate.mean_volume / container_volume;
  estimate.capacity = kMaxSolidFraction * container_volume / estimate.mean_volume;
  if (is_library) {
    estimate.bytes_per_particle = kRandomLibraryBytesPerItem;
    estimate.bytes = estimate.particles * estimate.bytes_per_particle +
                     static_cast<double>(library_count) * (sample.mean_bytes + 72.0);
    estimate.seconds = run_seconds(sample, static_cast<double>(library_count), estimate.particles);
  } else {
    estimate.bytes_per_particle = kRandomBytesPerItem + sample.mean_bytes;
    estimate.bytes = estimate.particles * estimate.bytes_per_particle;
    estimate.seconds = run_seconds(sample, estimate.particles, estimate.particles);
  }
  return estimate;
}

RunEstimate estimate_run(const LatticeOptions& options, double sites) {
  const GrowthParams params = growth_params(options);
  const int count = sample_size_for(
      estimated_vertex_count(options.radius, options.edge_length, options.form.growth),
      static_cast<std::uint64_t>(std::max(1.0, sites)));
  const ShapeLibrary* files = options.files.loaded.get();
  const ShapeSample sample =
      files != nullptr
          ? sample_shapes(std::min<int>(count, static_cast<int>(std::min<std::size_t>(
                                                   files->shapes.size(), 1000))),
                          [&](std::uint64_t k) {
                            return std::make_pair(files->shapes[k].body.scaled(options.radius),
                                                  options.radius);
                          })
          : sample_shapes(count, [&](std::uint64_t i) {
              Rng rng(options.seed, i);
              return std::make_pair(grow_aggregate(params, rng), options.radius);
            });
  RunEstimate estimate;
  const double container_volume = options.container.volume();
  estimate.particles = sites;
  estimate.mean_volume =
      sample.volume_ratio * 4.0 / 3.0 * std::numbers::pi * std::pow(options.radius, 3);
  estimate.solid_fraction = sites * estimate.mean_volume / container_volume;
  estimate.capacity = kMaxSolidFraction * container_volume / estimate.mean_volume;
  if (files != nullptr) {  // one stored copy per library shape, not per site
    estimate.bytes_per_particle = kRandomLibraryBytesPerItem;
    estimate.bytes = sites * estimate.bytes_per_particle +
                     static_cast<double>(files->shapes.size()) * (sample.mean_bytes + 72.0);
    estimate.seconds = run_seconds(sample, static_cast<double>(files->shapes.size()), sites);
  } else {
    estimate.bytes_per_particle = kLatticeBytesPerSite + sample.mean_bytes;
    estimate.bytes = sites * estimate.bytes_per_particle;
    estimate.seconds = run_seconds(sample, sites, sites);
  }
  return estimate;
}

void check_resources(const RandomPackOptions& options) {
  const RunEstimate estimate = estimate_run(options);
  const bool is_count = options.target == PackTarget::kCount;
  const std::string field = is_count ? "random.count" : "random.volume_fraction";
  const std::string value =
      is_count ? std::to_string(options.count) : format_value(options.volume_fraction);
  if (!(estimate.mean_volume > 0.0) || !std::isfinite(estimate.mean_volume)) {
    throw LimitExceeded(
        Wording{Sentence::kText, {"grading"}},
        Wording{Sentence::kSizesFrom, {format_value(smallest_size(options.grading))}},
        Wording{Sentence::kPositiveVolume, {format_value(estimate.mean_volume)}});
  }
  if (is_count && estimate.solid_fraction > kMaxSolidFraction) {
    throw LimitExceeded(
        field, value,
        Wording{Sentence::kContainerCapacity,
                {count_text(estimate.capacity), format_value(options.container.volume()),
                 format_value(kMaxSolidFraction), count_text(estimate.particles),
                 volume_text(estimate.mean_volume), count_text(estimate.solid_fraction)}});
  }
  const MemoryLimit limit = memory_limit();
  if (estimate.bytes > limit.bytes) {
    throw LimitExceeded(field, value,
                        memory_advice(estimate, limit,
                                      english_words(options.shape.library_size > 0
                                                        ? Sentence::kPhraseUseLargerParticles
                                                        : Sentence::kPhraseUseLibrarySize)));
  }
  // Every library shape is grown before placement: a library far larger than the particles the
  // target needs costs memory and time for shapes never used (the packing stores only used ones).
  // Refused only when growing it is heavy (above kHeavyBytes or kHeavySeconds, the heads-up's
  // thresholds): a few thousand spare shapes cost megabytes and a second or two.
  const double library = options.shape.library_size;
  const double most = std::max(kLibraryFloor, std::ceil(kLibraryHeadroom * estimate.particles));
  const double library_bytes = estimate.bytes - estimate.particles * estimate.bytes_per_particle;
  const double library_seconds =
      estimate.seconds - estimate.particles * kPlacementSecondsPerParticle;
  if (library > most && (library_bytes > kHeavyBytes || library_seconds > kHeavySeconds)) {
    char seconds[32];
    std::snprintf(seconds, sizeof seconds, "%.2g", library_seconds);
    throw LimitExceeded(
        "shape.library_size", std::to_string(options.shape.library_size),
        Wording{Sentence::kLibraryHeadroom,
                {count_text(most), format_value(kLibraryHeadroom), count_text(estimate.particles),
                 count_text(kLibraryFloor), format_bytes(estimate.bytes), seconds}});
  }
}

void check_resources(const LatticeOptions& options, double sites) {
  const RunEstimate estimate = estimate_run(options, sites);
  if (!(estimate.mean_volume > 0.0) || !std::isfinite(estimate.mean_volume)) {
    throw LimitExceeded(
        "lattice.radius", format_value(options.radius),
        Wording{Sentence::kRadiusPositiveVolume, {format_value(estimate.mean_volume)}});
  }
  const MemoryLimit limit = memory_limit();
  if (estimate.bytes > limit.bytes) {
    throw LimitExceeded(
        "lattice.radius", format_value(options.radius),
        memory_advice(estimate, limit, english_words(Sentence::kPhraseUseLargerRadius)));
  }
}

RunEstimate estimate_densify(double particles, double max_sweeps, double max_seconds, int threads) {
  RunEstimate estimate;
  estimate.particles = particles;
  estimate.bytes = particles * kDensifyBytesPerParticle;
  estimate.seconds =
      particles * max_sweeps * kDensifySecondsPerParticleSweep / std::max(1, threads);
  if (max_seconds > 0.0) estimate.seconds = std::min(estimate.seconds, max_seconds);
  estimate.is_upper_bound = true;
  return estimate;
}

RunEstimate estimate_simulation(double bodies, double shape_bytes, double steps, double runs,
                                int parallel) {
  RunEstimate estimate;
  const double at_once = std::min(runs, static_cast<double>(std::max(1, parallel)));
  estimate.particles = bodies;
  estimate.bytes = at_once * (bodies * kSimBytesPerBody + 2.0 * shape_bytes);
  const double per_body_step =
      kSimSecondsPerBodyStep * std::pow(std::max(1.0, bodies / 1000.0), kSimCostExponent);
  estimate.seconds = std::ceil(runs / at_once) * bodies * steps * per_body_step;
  return estimate;
}

double expected_steps(double height, double min_time, double quiet_time, double max_time,
                      double time_step) {
  const double fall = std::sqrt(2.0 * std::max(0.0, height) / kGravity);
  const double simulated = std::min(max_time, min_time + 2.0 * fall + quiet_time + 1.0);
  return time_step > 0.0 ? simulated / time_step : 0.0;
}

double automatic_time_step(double d_min, double time_step_factor) {
  return time_step_factor * std::sqrt(std::max(d_min, 0.0) / kGravity);
}

RunEstimate estimate_mesomodel(double particles, double voxels) {
  RunEstimate estimate;
  estimate.particles = particles;
  if (voxels > 0.0) {
    estimate.bytes = voxels * kVoxelBytes;
    estimate.seconds = voxels * kVoxelSeconds;
  } else {
    estimate.bytes = particles * kMeshBytesPerAggregate;
    estimate.seconds = particles * kMeshSecondsPerAggregate;
  }
  return estimate;
}

double estimated_tetgen_elements(double triangles, double volume, double max_volume) {
  const double bounded = max_volume > 0.0 ? 0.45 * volume / max_volume : 0.0;
  return std::max(1.5 * triangles, bounded);
}

RunEstimate estimate_export(const ExportWork& work) {
  RunEstimate estimate;
  estimate.particles = work.particles;
  const double threads = std::max(1, allowed_threads());
  estimate.seconds =
      work.tetgen_shapes * kTetGenSecondsPerShape / threads +
      work.cells * (work.is_wide ? kExportWideSecondsPerCell : kExportSecondsPerCell);
  // TetGen's meshes are kept per shape: at most one per cell written (one shape per particle).
  const double tetgen_cells = work.tetgen_shapes > 0.0 ? work.cells : 0.0;
  estimate.bytes = work.shape_bytes + work.particles * static_cast<double>(sizeof(Particle)) +
                   tetgen_cells * kTetGenBytesPerElement;
  estimate.output_bytes =
      work.cells * (work.is_wide ? kExportWideBytesPerCell : kExportBytesPerCell);
  return estimate;
}

RunEstimate estimate_render(double particles, double shape_bytes, double pixels, int samples) {
  RunEstimate estimate;
  estimate.particles = particles;
  estimate.seconds = kRenderSetupSeconds + particles * kRenderSecondsPerParticle;
  estimate.bytes =
      3.0 * shape_bytes + particles * kRenderBytesPerParticle + pixels * 4.0 * std::max(1, samples);
  return estimate;
}

RunEstimate estimate_shapes(const GeneratorOptions& options, double count, bool has_output) {
  const double vertices =
      estimated_vertex_count(options.radius_max, options.edge_length, options.form.growth);
  const int sample_count =
      std::min(sample_size_for(vertices, static_cast<std::uint64_t>(std::max(1.0, count))), 16);
  const ShapeSample sample = sample_shapes(sample_count, [&](std::uint64_t i) {
    GeneratedParticle particle = generate_particle(options, i);
    return std::make_pair(std::move(particle.body), particle.control_radius);
  });
  RunEstimate estimate;
  estimate.particles = count;
  estimate.seconds = count * sample.seconds_per_shape / std::max(1, allowed_threads());
  estimate.bytes = std::min(count, kShapesChunk) * kShapesBytesPerRow +
                   static_cast<double>(std::max(1, allowed_threads())) * sample.mean_bytes;
  if (has_output) estimate.output_bytes = count * kShapesBytesPerRow;
  return estimate;
}

std::string heavy_run_note(const RunEstimate& estimate) {
  if (!(estimate.seconds > kHeavySeconds) && !(estimate.bytes > kHeavyBytes) &&
      !(estimate.output_bytes > kHeavyBytes)) {
    return "";
  }
  const double seconds = estimate.seconds;
  char time[64];
  if (seconds < 120.0) {
    std::snprintf(time, sizeof time, "%.0f s", seconds);
  } else if (seconds < 7200.0) {
    std::snprintf(time, sizeof time, "%.0f min", seconds / 60.0);
  } else {
    std::snprintf(time, sizeof time, "%.1f h", seconds / 3600.0);
  }
  return "a large run: ~" + count_text(estimate.particles) + " particles, ~" +
         format_bytes(estimate.bytes) + " of memory, " +
         (estimate.output_bytes > 0.0 ? "~" + format_bytes(estimate.output_bytes) + " written, "
                                      : std::string()) +
         (estimate.is_upper_bound ? "up to ~" : "~") + time + " (rough estimate; Ctrl-C stops it)";
}

}  // namespace aggpack
