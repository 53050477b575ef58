// `aggpack particle` and `aggpack shapes`: make and measure particles (issue 2).

#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

#include "aggpack/config/schema.h"
#include "aggpack/core/atomic_file.h"
#include "aggpack/core/error.h"
#include "aggpack/core/parallel.h"
#include "aggpack/io/export.h"
#include "aggpack/io/shape_library_files.h"
#include "aggpack/pack/resources.h"
#include "aggpack/shape/descriptors.h"
#include "aggpack/shape/generator.h"
#include "commands.h"
#include "output_flags.h"
#include "progress.h"

namespace aggpack::cli {

namespace {

struct ShapeFlags {
  GeneratorOptions generator;
  std::string growth = "hull";
  double radius = 0;  // --radius sets both ends of the range
  int threads = 0;
};

void add_generator_options(CLI::App& command, ShapeFlags& flags) {
  auto& g = flags.generator;
  command.add_option("--alpha", g.alpha, "Eq. 3 shape control alpha, in [0, 1]")
      ->capture_default_str();
  command.add_option(
      "-r,--radius", flags.radius,
      "control radius r (m), > 0; sets --radius-min and --radius-max (default: unset)");
  command.add_option("--radius-min", g.radius_min, "smallest control radius (m), > 0")
      ->capture_default_str();
  command.add_option("--radius-max", g.radius_max, "largest control radius (m), >= radius-min")
      ->capture_default_str();
  command
      .add_option("-L,--edge-length", g.edge_length,
                  "maximum edge length L (m), > 0: growth stops when every edge <= L")
      ->capture_default_str();
  command
      .add_option("--growth", flags.growth,
                  "where a new vertex goes: hull (the paper's words: a random point of the "
                  "longest edge, out to its Eq. 3 distance, convex hull kept) or midpoint "
                  "(aggpack 0.1's rule, kept for earlier files)")
      ->capture_default_str();
  command
      .add_option("--elongation", g.form.elongation,
                  "control ellipsoid's intermediate / long semi-axis, [0.1, 1] (1 = sphere)")
      ->capture_default_str();
  command
      .add_option("--flatness", g.form.flatness,
                  "control ellipsoid's short / intermediate semi-axis, [0.1, 1] (1 = sphere)")
      ->capture_default_str();
  command
      .add_option("--min-edge-ratio", g.form.min_edge_ratio,
                  "minimum edge length / L (hull growth): the random point on the longest edge "
                  "is at least this x L from both ends, [0, 0.5]")
      ->capture_default_str();
  command.add_option("--max-vertices", g.max_vertices, "vertex cap per particle, [6, 1000000]")
      ->check(kNotNegative)
      ->capture_default_str();
  command
      .add_option("--seed", g.seed, "master seed, [0, 2^64-1]; particle i uses stream (seed, i)")
      ->check(kNotNegative)
      ->capture_default_str();
}

// Checks every flag under its own name (the library's checks name its struct fields), then the
// library's own validation, which adds the vertex-cap estimate.
void resolve_radius(ShapeFlags& flags, const CLI::App& command) {
  auto& g = flags.generator;
  require_in_range("--alpha", g.alpha, 0.0, 1.0);
  if (command.count("--radius") > 0) {
    if (command.count("--radius-min") > 0 || command.count("--radius-max") > 0) {
      throw InvalidInput("--radius", format_value(flags.radius),
                         "either --radius or --radius-min/--radius-max, not both");
    }
    require_positive("--radius", flags.radius);
    g.radius_min = flags.radius;
    g.radius_max = flags.radius;
  }
  require_positive("--radius-min", g.radius_min);
  require_positive("--radius-max", g.radius_max);
  if (g.radius_max < g.radius_min) {
    throw InvalidInput("--radius-max", format_value(g.radius_max),
                       ">= --radius-min = " + format_value(g.radius_min));
  }
  require_positive("--edge-length", g.edge_length);
  const auto growth = find_growth(flags.growth);
  if (!growth) throw InvalidInput("--growth", flags.growth, "hull or midpoint");
  g.form.growth = *growth;
  require_in_range("--elongation", g.form.elongation, 0.1, 1.0);
  require_in_range("--flatness", g.form.flatness, 0.1, 1.0);
  require_in_range("--min-edge-ratio", g.form.min_edge_ratio, 0.0, 0.5);
  with_key_names({}, {{"max_vertices", "--max-vertices"}, {"edge_length", "--edge-length"}},
                 [&] { validate(g); });
}

void print_descriptors(const ShapeDescriptors& d, double control_radius) {
  fmt::print("control radius       {:.6g} m\n", control_radius);
  for (const auto& column : descriptor_columns()) {
    fmt::print("{:<20} {:.6g} {}\n", column.name, column.get(d),
               std::string(column.unit) == "-" ? "" : column.unit);
  }
}

// Where `shapes --library` reads from and how.
struct LibraryFlags {
  std::vector<std::string> paths;  // --library, repeated or comma-separated
  std::string units = "mm";
  bool is_skipping_bad = false;
  double max_hull_excess = 0.0;
  std::uint32_t max_vertices = 1000;
};

void print_summary(const std::vector<RunningSummary>& summaries) {
  const auto& columns = descriptor_columns();
  fmt::print("{:<22}{:>14}{:>14}{:>14}{:>14}\n", "descriptor", "mean", "std", "min", "max");
  for (std::size_t c = 0; c < columns.size(); ++c) {
    const auto s = summaries[c].result();
    fmt::print("{:<22}{:>14.6g}{:>14.6g}{:>14.6g}{:>14.6g}\n", columns[c].name, s.mean,
               s.standard_deviation, s.minimum, s.maximum);
  }
}

// `aggpack shapes --library DIR`: every library shape at its file size, one CSV row each (the
// generated particles' columns, then the file, its hash and what the hull and the vertex budget
// changed), then the import summary and the descriptors' summary.
void run_library(const LibraryFlags& flags, const std::string& output, Overwrite overwrite) {
  if (flags.units != "mm" && flags.units != "m") {
    throw InvalidInput("--units", flags.units, "mm or m");
  }
  ShapeLibraryOptions options{
      .paths = flags.paths,
      .import = {.units = flags.units == "m" ? LengthUnit::kMetre : LengthUnit::kMillimetre,
                 .max_hull_excess = flags.max_hull_excess,
                 .max_vertices = flags.max_vertices},
      .is_skipping_bad = flags.is_skipping_bad};
  require_in_range("--max-hull-excess", flags.max_hull_excess, 0.0, 100.0);
  if (flags.max_vertices < 4 || flags.max_vertices > 1000000) {
    throw InvalidInput("--max-hull-vertices", std::to_string(flags.max_vertices), "[4, 1000000]");
  }
  for (const std::string& path : flags.paths) {
    if (path.empty()) {
      throw InvalidInput("--library", "\"\"", "a folder or a .stl, .obj or .ply file");
    }
  }
  if (!output.empty()) check_writable(output, overwrite);
  ShapeLibrary library;
  // The loader's messages name the config keys; here the user typed flags.
  with_key_names({},
                 {{"particle.library", "--library"},
                  {"particle.library_max_hull_excess", "--max-hull-excess"}},
                 [&] { library = load_shape_library(options); });
  const auto& columns = descriptor_columns();
  std::vector<ShapeDescriptors> descriptors(library.shapes.size());
  parallel_for_index(0, library.shapes.size(), [&](std::size_t k) {
    const LibraryShape& shape = library.shapes[k];
    descriptors[k] = describe(shape.body.scaled(shape.size / 2.0));
  });
  std::string csv = "index,control_radius";
  for (const auto& column : columns) csv += "," + std::string(column.name);
  csv += ",file,hash,mesh_volume,hull_volume,hull_excess,simplification_change\n";
  std::vector<RunningSummary> summaries(columns.size());
  double hull_total = 0.0;
  double kept_total = 0.0;
  std::size_t simplified = 0;
  for (std::size_t k = 0; k < library.shapes.size(); ++k) {
    const LibraryShape& shape = library.shapes[k];
    csv += fmt::format("{},{:.17g}", k, shape.size / 2.0);
    for (std::size_t c = 0; c < columns.size(); ++c) {
      const double value = columns[c].get(descriptors[k]);
      summaries[c].add(value);
      csv += fmt::format(",{:.17g}", value);
    }
    csv += fmt::format(",{},{},{:.17g},{:.17g},{:.17g},{:.17g}\n", shape.name, shape.hash,
                       shape.mesh_volume, shape.hull_volume, shape.hull_excess(),
                       shape.simplification_change());
    hull_total += shape.hull_volume;
    kept_total += shape.volume;
    simplified += shape.volume != shape.hull_volume ? 1 : 0;
  }
  if (output.empty()) {
    fmt::print("{}", csv);
  } else {
    AtomicFile file(output, overwrite, std::ios::out);
    file.stream() << csv;
    file.commit();
    fmt::print("wrote {} ({} shapes)\n", output, library.shapes.size());
  }
  fmt::print("library         {}\n", library.summary());
  for (const std::string& line : library.skipped) fmt::print("skipped         {}\n", line);
  fmt::print("convex hulls    {}\n", library.hull_summary());
  fmt::print(
      "vertex budget   {} of {} hulls simplified to <= {} vertices ({:+.3f} % of hull "
      "volume)\n",
      simplified, library.shapes.size(), flags.max_vertices,
      100.0 * (kept_total / hull_total - 1.0));
  print_summary(summaries);
}

}  // namespace

void set_thread_count(int threads) {
  if (threads < 0) throw InvalidInput("--threads", std::to_string(threads), ">= 0 (0 = all cores)");
  limit_threads(threads);
}

void register_particle(CLI::App& app) {
  auto flags = std::make_shared<ShapeFlags>();
  auto output = std::make_shared<std::string>();
  auto index = std::make_shared<std::uint64_t>(0);
  auto is_ascii = std::make_shared<bool>(false);
  auto is_forced = std::make_shared<bool>(false);
  auto scale = std::make_shared<double>(1.0);
  auto* command =
      app.add_subcommand("particle",
                         "Generate one random aggregate particle, print its shape descriptors and "
                         "optionally write it as STL.");
  add_generator_options(*command, *flags);
  command->add_option("--index", *index, "particle index within the seed's family, >= 0")
      ->check(kNotNegative)
      ->capture_default_str();
  command->add_option("-o,--output", *output, "STL file to write (omit to only measure)");
  command->add_flag("--ascii", *is_ascii, "write ASCII STL instead of binary");
  command->add_option("--scale", *scale, "multiply coordinates by this in the STL (1000 = mm)")
      ->capture_default_str();
  command->add_flag("-f,--force", *is_forced, "replace an existing output file");
  command->callback([=, &app]() {
    const auto* self = app.get_subcommand("particle");
    resolve_radius(*flags, *self);
    if (self->count("--output") > 0) check_output_file_flag("-o/--output", *output);
    require_positive("--scale", *scale);
    const Overwrite overwrite = *is_forced ? Overwrite::kAllow : Overwrite::kForbid;
    if (!output->empty()) check_writable(*output, overwrite);
    const GeneratedParticle particle = generate_particle(flags->generator, *index);
    if (!output->empty()) {
      Packing packing;  // the particle as it was grown: one shape, identity pose
      packing.shapes.push_back(particle.body);
      packing.particles.emplace_back();
      write(packing, *output,
            {.format = ExportFormat::kStl,
             .scale = *scale,
             .overwrite = overwrite,
             .stl_encoding = *is_ascii ? StlEncoding::kAscii : StlEncoding::kBinary});
      fmt::print("wrote {}\n", *output);
    }
    print_descriptors(describe(particle.body), particle.control_radius);
  });
}

void register_shapes(CLI::App& app) {
  auto flags = std::make_shared<ShapeFlags>();
  auto output = std::make_shared<std::string>();
  auto count = std::make_shared<std::uint64_t>(1000);
  auto is_forced = std::make_shared<bool>(false);
  auto* command = app.add_subcommand(
      "shapes",
      "Generate N particles in parallel; write a CSV of their descriptors and print a "
      "summary (mean, std, min, max).");
  add_generator_options(*command, *flags);
  command->add_option("-n,--count", *count, "number of particles, [1, 100000000]")
      ->check(kNotNegative)
      ->capture_default_str();
  command->add_option("-o,--output", *output, "CSV file to write (omit to print the summary only)");
  command->add_option("-j,--threads", flags->threads, "worker threads (0 = all cores)")
      ->capture_default_str();
  command->add_flag("-f,--force", *is_forced, "replace an existing output file");
  auto progress = std::make_shared<std::string>("auto");
  command
      ->add_option("--progress", *progress,
                   "particles grown, rate and ETA on stderr for a run of 2 s or more: auto "
                   "(redrawn on a terminal, else a line every 2 s), bar, lines, none")
      ->capture_default_str();
  auto library = std::make_shared<LibraryFlags>();
  command
      ->add_option("--library", library->paths,
                   "measure a shape library instead of growing particles: a folder of .stl, "
                   ".obj, .ply meshes or one such file (repeat the flag or separate with commas "
                   "for several); each as its convex hull at file size")
      ->delimiter(',');
  command->add_option("--units", library->units, "--library: unit of the files (mm or m)")
      ->capture_default_str();
  command->add_flag("--skip-bad", library->is_skipping_bad,
                    "--library: skip and count bad meshes instead of stopping at the first");
  command
      ->add_option("--max-hull-excess", library->max_hull_excess,
                   "--library: refuse a shape whose hull adds more than this fraction of its "
                   "volume, [0, 100] (0 = no limit)")
      ->capture_default_str();
  command
      ->add_option("--max-hull-vertices", library->max_vertices,
                   "--library: simplify hulls to at most this many vertices, [4, 1000000]")
      ->check(kNotNegative)
      ->capture_default_str();
  command->callback([=, &app]() {
    const auto* self = app.get_subcommand("shapes");
    if (self->count("--library") > 0) {
      set_thread_count(flags->threads);
      run_library(*library, *output, *is_forced ? Overwrite::kAllow : Overwrite::kForbid);
      return;
    }
    resolve_radius(*flags, *self);
    if (self->count("--output") > 0) check_output_file_flag("-o/--output", *output);
    if (*count < 1 || *count > 100000000ULL) {
      throw InvalidInput("-n/--count", std::to_string(*count), "[1, 100000000]");
    }
    const ProgressStyle style = parse_progress_style("--progress", *progress);
    set_thread_count(flags->threads);
    const Overwrite overwrite = *is_forced ? Overwrite::kAllow : Overwrite::kForbid;
    if (!output->empty()) check_writable(*output, overwrite);
    const RunEstimate estimate =
        estimate_shapes(flags->generator, static_cast<double>(*count), !output->empty());
    announce_heavy_run(estimate);

    // Generated in chunks (in parallel), written and summarised in index order: memory stays
    // bounded by one chunk however large --count is (issue 12). A chunk is small enough for the
    // progress display to move every fraction of a second.
    const auto n = static_cast<std::size_t>(*count);
    constexpr std::size_t kChunk = 8192;
    // The display: from the start for a run estimated at progress_delay() (2 s) or more, else
    // from when it has taken that long (a short run prints nothing).
    const double delay = progress_delay();
    const auto start = std::chrono::steady_clock::now();
    std::unique_ptr<ProgressBar> bar;
    const auto show_progress = [&](std::size_t done) {
      const double elapsed =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      if (!bar && (estimate.seconds >= delay || elapsed >= delay)) {
        bar = std::make_unique<ProgressBar>("growing", "particles", style);
        bar->set_start(start);
      }
      if (bar) {
        bar->update(static_cast<double>(done) / static_cast<double>(n), done, n);
      }
    };
    show_progress(0);
    const auto& columns = descriptor_columns();
    std::vector<RunningSummary> summaries(columns.size());
    std::unique_ptr<AtomicFile> file;
    if (!output->empty()) {
      file = std::make_unique<AtomicFile>(*output, overwrite, std::ios::out);
      file->stream() << "index,control_radius";
      for (const auto& column : columns) file->stream() << ',' << column.name;
      file->stream() << '\n';
    }
    std::vector<ShapeDescriptors> descriptors;
    std::vector<std::string> rows;  // each particle's CSV line, formatted by its thread
    for (std::size_t begin = 0; begin < n; begin += kChunk) {
      const std::size_t size = std::min(kChunk, n - begin);
      descriptors.assign(size, ShapeDescriptors{});
      rows.assign(size, std::string());
      auto make = [&](std::size_t k) {
        const auto particle = generate_particle(flags->generator, begin + k);
        descriptors[k] = describe(particle.body);
        if (!file) return;
        auto row = std::back_inserter(rows[k]);
        fmt::format_to(row, "{},{:.17g}", begin + k, particle.control_radius);
        for (const auto& column : columns)
          fmt::format_to(row, ",{:.17g}", column.get(descriptors[k]));
        rows[k] += '\n';
      };
      parallel_for_index(0, size, make);
      for (std::size_t k = 0; k < size; ++k) {
        for (std::size_t c = 0; c < columns.size(); ++c) {
          summaries[c].add(columns[c].get(descriptors[k]));
        }
        if (file) file->stream() << rows[k];
      }
      show_progress(begin + size);
    }
    bar.reset();  // its final line, before the summary
    if (file) {
      file->commit();
      fmt::print("wrote {} ({} particles)\n", *output, n);
    }
    print_summary(summaries);
  });
}

}  // namespace aggpack::cli
