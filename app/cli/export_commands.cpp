// `aggpack export`: turn a native packing file into any format of the format table
// (export_formats(): STL, rock.dat, Abaqus, VTK, Gmsh, LS-DYNA, ANSYS, OBJ, YADE, native .h5;
// issue 4). The format lists of the help text come from that table.

#include <fmt/core.h>

#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "aggpack/config/schema.h"
#include "aggpack/core/error.h"
#include "aggpack/core/text.h"
#include "aggpack/geom/mass_properties.h"
#include "aggpack/io/export.h"
#include "aggpack/io/native.h"
#include "aggpack/mesh/quality.h"
#include "aggpack/pack/resources.h"
#include "commands.h"
#include "output_flags.h"
#include "progress.h"
#include "quality_verdict.h"

namespace aggpack::cli {

namespace {

struct ExportFlags {
  std::string input;
  std::string output;
  std::string format;
  ExportOptions options;
  bool is_forced = false;
  bool is_ascii = false;
  bool is_surface_split = false;
  std::string cells = "default";
  std::string tet_method = "fan";
  std::string inp_layout = "sets";
  std::string deck = "none";
  int threads = 0;
  std::string progress = "auto";
};

// The names (or titles) of the formats whose row `has` something, joined by `separator`.
std::string formats_where(bool (*has)(const FormatInfo&), std::string_view separator,
                          std::string_view FormatInfo::*field = &FormatInfo::name) {
  std::string text;
  for (const FormatInfo& info : export_formats()) {
    if (!has(info)) continue;
    if (!text.empty()) text += separator;
    text += info.*field;
  }
  return text;
}

bool is_any(const FormatInfo& /*info*/) { return true; }
bool has_per_particle(const FormatInfo& info) { return info.has_per_particle; }
bool has_ascii(const FormatInfo& info) { return info.has_ascii; }
bool has_quadratic(const FormatInfo& info) { return info.has_quadratic; }
bool holds_packing(const FormatInfo& info) { return info.holds_packing; }
bool has_both_cells(const FormatInfo& info) { return info.has_surface && info.has_tetrahedra; }

// "abaqus | calculix | ...": every deck's name.
std::string deck_names(std::string_view separator) {
  std::string text;
  for (const DeckInfo& deck : deck_kinds()) {
    if (!text.empty()) text += separator;
    text += deck.name;
  }
  return text;
}

// ".inp, .inp, .k, .py": the format of every deck, in deck order.
std::string deck_formats() {
  std::string text;
  for (const DeckInfo& deck : deck_kinds()) {
    if (!text.empty()) text += ", ";
    text += "." + format_name(deck.format);
  }
  return text;
}

// "vtu surface, msh tetrahedra": the default cells of the formats that hold either.
std::string default_cells_text() {
  std::string text;
  for (const FormatInfo& info : export_formats()) {
    if (!has_both_cells(info)) continue;
    if (!text.empty()) text += ", ";
    text += fmt::format("{} {}", info.name,
                        info.default_cells == MeshCells::kSurface ? "surface" : "tetrahedra");
  }
  return text;
}

// At most this many shape numbers and particle names are listed; the count is always complete.
constexpr std::size_t kListedFallbacks = 20;

// "tetgen: 4 of 1050 shapes fell back to the centroid fan (shapes 324, ...; particles P325, ...;
// TetGen died of signal 6 (Aborted): 4)".
std::string tetgen_report(const ExportSummary& summary) {
  const auto& fallbacks = summary.tetgen_fallbacks;
  if (fallbacks.empty()) {
    return fmt::format("tetgen: all {} shapes meshed by TetGen, none fell back to the centroid fan",
                       summary.tetgen_shapes);
  }
  std::string shapes;
  std::string particles;
  std::size_t particle_count = 0;
  std::map<std::string, std::size_t> failures;
  for (std::size_t i = 0; i < fallbacks.size(); ++i) {
    ++failures[fallbacks[i].failure];
    if (i < kListedFallbacks) shapes += fmt::format("{}{}", i == 0 ? "" : ", ", fallbacks[i].shape);
    for (const std::uint64_t number : fallbacks[i].particles) {
      if (particle_count++ < kListedFallbacks) {
        particles += fmt::format("{}P{}", particles.empty() ? "" : ", ", number);
      }
    }
  }
  if (fallbacks.size() > kListedFallbacks) {
    shapes += fmt::format(" and {} more", fallbacks.size() - kListedFallbacks);
  }
  if (particle_count > kListedFallbacks) {
    particles += fmt::format(" and {} more", particle_count - kListedFallbacks);
  }
  std::string reasons;
  for (const auto& [failure, count] : failures) {
    reasons += fmt::format("; {}: {}", failure, count);
  }
  return fmt::format(
      "tetgen: {} of {} shapes fell back to the centroid fan (shape{} {}; {} particle{} {}{})",
      fallbacks.size(), summary.tetgen_shapes, fallbacks.size() == 1 ? "" : "s", shapes,
      particle_count, particle_count == 1 ? "" : "s", particles, reasons);
}

// The library's names of the values these flags set (export.h, mesh/tetrahedra.h); messages
// name the flag typed.
const std::map<std::string, std::string>& export_flag_names() {
  static const std::map<std::string, std::string> names = {
      {"scale", "--scale"},
      {"compression", "--compression"},
      {"max tetrahedron volume", "--max-volume"},
      {"radius-edge ratio", "--radius-edge"},
      {"TetGen time limit (s)", "--tet-time-limit"},
      {"material name", "--material-name"},
      {"density", "--density"},
      {"youngs modulus", "--youngs-modulus"},
      {"poisson ratio", "--poisson-ratio"},
      {"friction", "--friction"},
      {"gravity", "--gravity"},
      {"baffle position", "--baffle-position"},
      {"trough length", "--trough-length"},
      {"baffle speed", "--baffle-speed"},
      {"settle time", "--settle-time"},
      {"rest time", "--rest-time"},
      {"contact distance", "--contact-distance"},
      {"time step", "--time-step"},
      {"deck", "--deck"},
      {"per-particle", "--per-particle"},
      {"cut-to-box", "--cut-to-box"},
      {"inp layout", "--inp-layout"},
      {"quadratic", "--quadratic"},
      {"xdmf", "--xdmf"},
      {"cells", "--cells"},
      {"output extension", "-o/--output extension"},
  };
  return names;
}

// What this export will write (for the heads-up and the TetGen stage's ETA): the cells of every
// particle, TetGen's per shape estimated from its triangles and volume (resources.h).
ExportWork export_work(const Packing& packing, const ExportOptions& options) {
  const FormatInfo& info = format_info(options.format);
  const MeshCells cells = options.cells == MeshCells::kDefault ? info.default_cells : options.cells;
  const bool is_tetra =
      options.is_quadratic || (info.has_tetrahedra && cells != MeshCells::kSurface);
  const bool is_tetgen = is_tetra && options.tetrahedra.method == TetMethod::kTetGen;
  ExportWork work{.particles = static_cast<double>(packing.particles.size()),
                  .is_wide = options.is_quadratic ||
                             (info.has_ascii && options.stl_encoding == StlEncoding::kAscii)};
  std::vector<double> cells_of(packing.shapes.size(), -1.0);  // -1: not used
  for (const ConvexPolyhedron& shape : packing.shapes) work.shape_bytes += heap_bytes(shape);
  if (!info.has_surface && !info.has_tetrahedra) return work;  // the native file: no cells
  for (const Particle& particle : packing.particles) {
    double& count = cells_of.at(particle.shape);
    if (count < 0.0) {
      const ConvexPolyhedron& shape = packing.shapes[particle.shape];
      const auto triangles = static_cast<double>(shape.triangle_count());
      count = is_tetgen ? estimated_tetgen_elements(triangles, mass_properties(shape).volume,
                                                    options.tetrahedra.max_volume)
                        : triangles;
      work.tetgen_shapes += is_tetgen ? 1.0 : 0.0;
    }
    work.cells += count;
  }
  return work;
}

}  // namespace

std::string describe_quality(const TetQuality& quality) {
  return fmt::format(
      "min dihedral angle {:.2f} deg, max aspect ratio {:.3g} (circumradius / 3 inradius, "
      "1 = regular), {} of {} below {} deg",
      quality.min_dihedral_degrees, quality.max_aspect_ratio, quality.below_10_degrees,
      quality.tetrahedra, kPoorDihedralDegrees);
}

std::string quality_json(const TetQuality& quality) {
  // Degenerate tetrahedra have an infinite aspect ratio, which JSON cannot hold: null.
  const auto number = [](double value) {
    return std::isfinite(value) ? fmt::format("{}", value) : std::string("null");
  };
  return fmt::format(
      "{{\"tetrahedra\": {}, \"min_dihedral_deg\": {}, \"max_aspect_ratio\": {}, "
      "\"below_10_deg\": {}}}",
      quality.tetrahedra, number(quality.min_dihedral_degrees), number(quality.max_aspect_ratio),
      quality.below_10_degrees);
}

void register_export(CLI::App& app) {
  auto flags = std::make_shared<ExportFlags>();
  auto& defaults = flags->options;
  auto* command = app.add_subcommand(
      "export",
      fmt::format("Write a packing (native .h5 file from `aggpack pack`) as {}. Particles are "
                  "named P1, P2, ... in every format; docs/formats.md gives each layout.",
                  formats_where(is_any, ", ", &FormatInfo::title)));
  command->add_option("input", flags->input, "native packing file (.h5)")->required();
  command
      ->add_option("-o,--output", flags->output,
                   "file to write (a folder with --per-particle); the extension picks the "
                   "format unless --format is given")
      ->required();
  command->add_option("--format", flags->format,
                      fmt::format("{} (default: from the output extension; {} for a "
                                  "--per-particle folder without one)",
                                  formats_where(is_any, " | "),
                                  format_name(resolve_format("", {.is_per_particle = true}))));
  command->add_flag("-f,--force", flags->is_forced, "replace an existing output file or folder");
  command
      ->add_option("--scale", defaults.scale,
                   "multiply coordinates by this (1000 writes millimetres), > 0")
      ->capture_default_str();
  command->add_flag("--per-particle", defaults.is_per_particle,
                    formats_where(has_per_particle, "/") +
                        ": one file per particle (P000001.stl, ...) in the output folder");
  command->add_flag("--cut-to-box", defaults.is_cut_to_box,
                    "stl, periodic packings: every particle and its periodic images clipped to "
                    "the box (copies of the file tile space)");
  command->add_flag("--ascii", flags->is_ascii,
                    formats_where(has_ascii, "/") + ": ASCII instead of binary");
  command
      ->add_option("--cells", flags->cells,
                   fmt::format("{}: surface | tetrahedra (default: {})",
                               formats_where(has_both_cells, "/"), default_cells_text()))
      ->capture_default_str();
  command
      ->add_option("--tet-method", flags->tet_method,
                   "tetrahedra: fan (the paper's centroid fan, exact volume) | tetgen "
                   "(quality mesh)")
      ->capture_default_str();
  command
      ->add_option("--max-volume", defaults.tetrahedra.max_volume,
                   "tetgen: largest tetrahedron volume (m^3 of the stored shape), 0 = no bound")
      ->capture_default_str();
  command
      ->add_option("--radius-edge", defaults.tetrahedra.radius_edge_ratio,
                   "tetgen: radius-edge ratio bound, [1.2, 10]")
      ->capture_default_str();
  command
      ->add_option("--tet-time-limit", defaults.tetrahedra.time_limit,
                   "tetgen: seconds TetGen may spend on one shape before it is stopped and the "
                   "shape is cut as the centroid fan instead, [0.001, 604800]")
      ->capture_default_str();
  command->add_flag("--split-surface", flags->is_surface_split,
                    "tetgen: let TetGen add nodes on the surface too (bounds met everywhere; "
                    "surface then within ~1e-5 of the particle)");
  command->add_flag("--quadratic", defaults.is_quadratic,
                    formats_where(has_quadratic, "/") + ": C3D10 instead of C3D4");
  command
      ->add_option("--compression", defaults.compression,
                   formats_where(holds_packing, "/") + ": deflate level of the datasets, 0 .. 9")
      ->capture_default_str();
  command->add_flag("--xdmf", defaults.write_xdmf,
                    formats_where(holds_packing, "/") +
                        ": also store world-coordinate surfaces and write <output>.xdmf");
  command
      ->add_option("--inp-layout", flags->inp_layout,
                   "inp: sets (flat model, element/node set per particle; CalculiX reads it) "
                   "| parts (one part + instance per particle)")
      ->capture_default_str();
  command->add_option("--material-name", defaults.material.name, "inp/k/mac/py: material name")
      ->capture_default_str();
  command->add_option("--density", defaults.material.density, "material density (kg/m^3), > 0")
      ->capture_default_str();
  command
      ->add_option("--youngs-modulus", defaults.material.youngs_modulus,
                   "Young's modulus E (Pa), > 0")
      ->capture_default_str();
  command
      ->add_option("--poisson-ratio", defaults.material.poisson_ratio,
                   "Poisson's ratio nu, in (-1, 0.5)")
      ->capture_default_str();
  auto& deck = defaults.deck;
  command
      ->add_option("--deck", flags->deck,
                   fmt::format("none | {}: write a complete, runnable model of the paper's "
                               "trough test around the mesh (walls, moving baffle, gravity, "
                               "friction, steps, output) instead of the mesh alone; picks the "
                               "format ({}). Run it with: abaqus job=NAME | ccx -i NAME | "
                               "lsdyna i=NAME.k | yade -n -x NAME.py",
                               deck_names(" | "), deck_formats()))
      ->capture_default_str();
  command
      ->add_option("--friction", deck.friction, "deck: Coulomb mu_s, particles and walls, [0, 10]")
      ->capture_default_str();
  command->add_option("--gravity", deck.gravity, "deck: gravity (m/s^2) along -z, > 0")
      ->capture_default_str();
  command
      ->add_option("--baffle-position", deck.baffle_position,
                   "deck: x of the baffle (m), >= the particles' largest x; 0 = the container's "
                   "end")
      ->capture_default_str();
  command
      ->add_option("--trough-length", deck.trough_length,
                   "deck: trough length (m) from its start; 0 = twice the start-to-baffle "
                   "length (the paper's baffle at the middle)")
      ->capture_default_str();
  command
      ->add_option("--baffle-speed", deck.baffle_speed, "deck: baffle speed (m/s) toward +x, > 0")
      ->capture_default_str();
  command
      ->add_option("--settle-time", deck.settle_time,
                   "deck: step SETTLE (s), baffle still; 0 = twice the free fall of the highest "
                   "particle")
      ->capture_default_str();
  command->add_option("--rest-time", deck.rest_time, "deck: step REST after the baffle (s), >= 0")
      ->capture_default_str();
  command
      ->add_option("--contact-distance", deck.contact_distance,
                   "calculix deck: contact pairs between particles (and walls) closer than "
                   "this (m); 0 = half the largest particle radius")
      ->capture_default_str();
  command
      ->add_option("--time-step", deck.time_step,
                   "yade deck: time step (s); 0 = from the particles' mass and contact stiffness")
      ->capture_default_str();
  command->add_option("-j,--threads", flags->threads, "worker threads (0 = all cores)")
      ->capture_default_str();
  command
      ->add_option("--progress", flags->progress,
                   "tetgen: elapsed time and ETA while the shapes are meshed, on stderr: auto "
                   "(redrawn on a terminal, else a line every 2 s), bar, lines, none")
      ->capture_default_str();

  command->callback([flags]() {
    ExportOptions options = flags->options;
    set_thread_count(flags->threads);
    options.overwrite = flags->is_forced ? Overwrite::kAllow : Overwrite::kForbid;
    options.stl_encoding = flags->is_ascii ? StlEncoding::kAscii : StlEncoding::kBinary;
    if (!flags->format.empty()) options.format = parse_export_format(flags->format);
    options.cells = parse_mesh_cells(flags->cells, "--cells");
    options.tetrahedra.method = parse_tet_method(flags->tet_method, "--tet-method");
    options.tetrahedra.is_surface_kept = !flags->is_surface_split;
    options.abaqus_layout = parse_abaqus_layout(flags->inp_layout, "--inp-layout");
    options.deck.kind = parse_deck_kind(flags->deck);
    // Check options and the destination before the (possibly long) read of the input.
    if (options.is_per_particle) {
      check_output_folder_flag("-o/--output", flags->output);
    } else {
      check_output_file_flag("-o/--output", flags->output);
    }
    with_key_names({}, export_flag_names(), [&] {
      options.format = resolve_format(flags->output, options);
      validate(options, options.format);
    });
    if (!options.is_per_particle) check_writable(flags->output, options.overwrite);

    const auto start = std::chrono::steady_clock::now();
    const ProgressStyle style = parse_progress_style("--progress", flags->progress);
    const Packing packing = read_packing(flags->input);
    const ExportWork work = export_work(packing, options);
    announce_heavy_run(estimate_export(work));
    ExportSummary summary;
    {
      // TetGen meshes the shapes in worker processes: the shapes done so far, their rate and
      // the ETA from it (before the first, the ETA of TetGen's share of the estimate), and the
      // per-shape time limit.
      std::optional<StageTimer> timer;
      const std::function<void(std::size_t, std::size_t)> count_shapes =
          [&timer](std::size_t done, std::size_t total) { timer->set_items(done, total); };
      if (work.tetgen_shapes > 0.0) {
        timer.emplace(
            "meshing shapes (TetGen)", style,
            StageTiming{
                .item_limit_seconds = options.tetrahedra.time_limit,
                .expected_seconds = estimate_export({.tetgen_shapes = work.tetgen_shapes}).seconds,
                .items_total = static_cast<std::uint64_t>(work.tetgen_shapes)});
        options.tetrahedra.on_progress = &count_shapes;
      }
      with_key_names({}, export_flag_names(),
                     [&] { summary = write(packing, flags->output, options); });
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    fmt::print("wrote {} ({}): {} particles, {} nodes, {} elements, {} file{} in {} s\n",
               flags->output, format_name(summary.format), summary.particles, summary.nodes,
               summary.elements, summary.files, summary.files == 1 ? "" : "s",
               format_seconds(seconds));
    if (summary.quality.tetrahedra > 0) {
      fmt::print("tetrahedron quality: {}\n", describe_quality(summary.quality));
      print_verdict("quality verdict: ",
                    tet_quality_verdict(summary.quality, options.tetrahedra, options.scale));
    }
    if (summary.tetgen_shapes > 0) fmt::print("{}\n", tetgen_report(summary));
  });
}

}  // namespace aggpack::cli
