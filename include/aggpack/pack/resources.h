#pragma once
// Up-front estimates of what a packing run needs (issue 12). Both packers grow every particle's
// shape before (random) or while (lattice) placing it, so a size list the container cannot hold
// or whose shapes exceed the memory would run for hours and end in std::bad_alloc or the OOM
// killer. validate(RandomPackOptions) and validate(LatticeOptions) call the checks below and
// refuse such runs before any work, naming the estimate and the limit.

#include <string>

#include "aggpack/geom/convex_polyhedron.h"
#include "aggpack/pack/lattice_packer.h"
#include "aggpack/pack/random_packer.h"
#include "aggpack/shape/generator.h"

namespace aggpack {

/// Solid fraction no packing of these particles is taken to exceed: 0.74, the densest packing of
/// equal spheres. Random sequential addition jams far below it (about 0.38 for spheres).
inline constexpr double kMaxSolidFraction = 0.74;

/// Memory a run may use.
struct MemoryLimit {
  double bytes = 0.0;
  std::string source;  ///< "80% of physical memory (23 GB)", "AGGPACK_MEMORY_LIMIT=2G", ...
  /// The source's parts, for its words in another language: the variable's text when set, else
  /// what the 80% are of ("physical memory", a Sentence::kPhrase* word) and its size.
  std::string set_text;
  std::string share_of;
  std::string share_bytes;
};

/// The environment variable AGGPACK_MEMORY_LIMIT (bytes, optional suffix K, M, G or T = powers
/// of 1024) when set; otherwise 80% of the smallest of the physical memory, the cgroup limit
/// (memory.max) and the address-space limit (ulimit -v).
/// \throw InvalidInput if AGGPACK_MEMORY_LIMIT is set but is not a positive size.
MemoryLimit memory_limit();

/// Bytes a polyhedron holds on the heap (vertices, triangles, allocator overhead).
double heap_bytes(const ConvexPolyhedron& body);

/// "950 B", "12.3 kB", "1.1 GB" (powers of 1000).
std::string format_bytes(double bytes);

/// What a packing run would ask for, estimated before any work from a sample of its shapes.
struct RunEstimate {
  double particles = 0.0;           ///< particles grown: count target exact, otherwise estimated
  double mean_volume = 0.0;         ///< expected solid volume per particle (m^3)
  double solid_fraction = 0.0;      ///< particles * mean_volume / container volume
  double capacity = 0.0;            ///< particles the container holds at kMaxSolidFraction
  double bytes_per_particle = 0.0;  ///< its shape (unless shared) plus the packer's bookkeeping
  double bytes = 0.0;               ///< peak memory of the run
  /// Rough wall time (s) on an otherwise idle machine: the sample's CPU time per shape for every
  /// shape grown, on the allowed threads, plus a fixed placement cost per particle. Measured, so
  /// not reproducible.
  double seconds = 0.0;
  /// `seconds` is a budget's worth (a sweep or simulated-time limit) that the run may stop well
  /// before: the note says "up to".
  bool is_upper_bound = false;
  /// Bytes the run writes (0 = not estimated): a heavy run's note says "~1.2 GB written".
  double output_bytes = 0.0;
};

/// Estimates for options that passed the packer's own range checks. The random packer's sample:
/// the shapes of its first draws (up to 64, fewer for shapes with many vertices), so the estimate
/// is deterministic for a seed.
RunEstimate estimate_run(const RandomPackOptions& options);
RunEstimate estimate_run(const LatticeOptions& options, double sites);

/// Throws LimitExceeded (field random.count or random.volume_fraction) when a count target's
/// solid volume exceeds kMaxSolidFraction of the container, or when estimate_run().bytes exceeds
/// memory_limit(); (field shape.library_size) when a shape library holds more than 10 x the
/// estimated particles (and more than 1000 shapes) and growing it would take more than
/// kHeavyBytes or kHeavySeconds. Called by validate(RandomPackOptions).
void check_resources(const RandomPackOptions& options);
/// Throws LimitExceeded (field lattice.radius) when the shapes of `sites` lattice sites exceed
/// memory_limit(). Called by validate(LatticeOptions).
void check_resources(const LatticeOptions& options, double sites);

/// The other heavy commands, from per-unit costs measured in bench/RESULTS.md (one thread unless
/// said; `particles` is what RunEstimate::particles reports):
/// densify: `particles` particles, at most `max_sweeps` sweeps (and `max_seconds` of wall time
/// when > 0) on `threads` threads; the sweep budget's time, an upper bound (a run ends at its
/// target). Memory per particle measured with the packing's shapes (10^5 particles: 530 MB).
RunEstimate estimate_densify(double particles, double max_sweeps, double max_seconds, int threads);
/// A Bullet simulation (settle, repose, their ensembles and sweeps): `runs` runs of `bodies`
/// bodies for about `steps` time steps each, `parallel` runs at a time; `shape_bytes` the heap
/// bytes of one run's shapes (heap_bytes).
RunEstimate estimate_simulation(double bodies, double shape_bytes, double steps, double runs,
                                int parallel);
/// Expected time steps of a simulation to rest: twice the free fall from `height` (m), the
/// criterion's `min_time` and `quiet_time` and one more second, at most `max_time` (simulated
/// s), over `time_step` (s). Piles measured at rest after ~1.2 s (50 mm cube, 199 particles).
double expected_steps(double height, double min_time, double quiet_time, double max_time,
                      double time_step);
/// The automatic Bullet time step for particles of equivalent diameter `d_min` (m):
/// time_step_factor x sqrt(d_min / 9.81), as World takes it when PhysicsOptions::time_step = 0.
double automatic_time_step(double d_min, double time_step_factor);
/// mesomodel: the tetrahedral mesh of `particles` aggregates (voxels = 0), or the phase image of
/// `voxels` voxels.
RunEstimate estimate_mesomodel(double particles, double voxels);

/// TetGen's tetrahedra for one shape of `triangles` surface triangles and volume `volume` (m^3)
/// under a volume bound `max_volume` (0 = none), the surface kept: 1.5 per surface triangle, or
/// 0.45 per bound's volume when more (the paper's 1,050 shapes: 58,487 without a bound, 80,230
/// with 1e-5 m^3).
double estimated_tetgen_elements(double triangles, double volume, double max_volume);

/// What an export writes (the CLI adds it up from the packing and the options).
struct ExportWork {
  double particles = 0.0;
  double cells = 0.0;          ///< elements or triangles written, all particles
  double tetgen_shapes = 0.0;  ///< shapes meshed by TetGen first (0: fan or a surface format)
  bool is_wide = false;        ///< C3D10 or ASCII STL: ~275 bytes a cell instead of ~85
  double shape_bytes = 0.0;    ///< heap_bytes of the packing's shapes
};
/// export: TetGen at 1 ms per shape on the allowed threads, then the cells formatted and
/// written (bench/RESULTS.md, "Exports": 100,000 particles, 3.65 M cells: C3D4 301 MB in 1.2 s,
/// C3D10 998 MB in 5.1 s); memory: the packing and TetGen's meshes (the writers stream).
RunEstimate estimate_export(const ExportWork& work);
/// render (3D, headless): ~1.5 s for the context, the read and the first frame, then ~80 us per
/// particle (bench/RESULTS.md, "Rendering": 1,050 particles 1.65 s, 100,000 in 9.05 s);
/// memory: the packing's shapes three times (packing, drawing data, GPU copy) and the image's
/// `pixels` x `samples`.
RunEstimate estimate_render(double particles, double shape_bytes, double pixels, int samples);
/// shapes -n: `count` particles of `options` grown and described on the allowed threads (a
/// sample of the first few timed, as estimate_run's), a CSV row each when `has_output`.
RunEstimate estimate_shapes(const GeneratorOptions& options, double count, bool has_output);

/// A run is heavy above either of these: it is announced before it starts.
inline constexpr double kHeavySeconds = 10.0;
inline constexpr double kHeavyBytes = 1e9;

/// One line announcing a heavy run ("a large run: ~600000 particles, ~4.8 GB of memory, ~3 min
/// (rough estimate; Ctrl-C stops it)"; "up to ~3 min" for an upper bound; ", ~1.2 GB written"
/// after the memory when output_bytes is set), or "" when the estimate is below kHeavySeconds
/// and kHeavyBytes (memory and output).
std::string heavy_run_note(const RunEstimate& estimate);

}  // namespace aggpack
