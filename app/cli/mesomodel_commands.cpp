// `aggpack mesomodel`: the concrete mesomodel of a packing (issue 16): the conforming tetrahedral
// mesh of aggregate, ITZ and mortar (mesh/mesomodel.h) written as .inp, .msh or .vtu, or with
// `--voxels N` the phase image (mesh/voxels.h) as .vti, or raw + JSON header for FFT solvers.

#include <fmt/core.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <utility>

#include "aggpack/config/schema.h"
#include "aggpack/core/atomic_file.h"
#include "aggpack/core/error.h"
#include "aggpack/core/text.h"
#include "aggpack/io/homogenize.h"
#include "aggpack/io/mesomodel_files.h"
#include "aggpack/io/native.h"
#include "aggpack/io/voxel_image.h"
#include "aggpack/mesh/mesomodel.h"
#include "aggpack/mesh/voxels.h"
#include "aggpack/pack/container.h"
#include "commands.h"
#include "output_flags.h"
#include "progress.h"
#include "quality_verdict.h"

namespace aggpack::cli {

namespace {

struct MesomodelFlags {
  std::string input;
  std::string output;
  double itz = 0.0;
  int resolution = 0;
  MesoOptions mesh;
  MesoFileOptions file;
  std::vector<std::string> materials;
  std::string units = "mm";
  std::string itz_kind = "solid";
  std::string solver = "direct";
  bool has_no_particle_sets = false;
  int threads = 0;
  std::string progress = "auto";
  bool is_forced = false;
  bool is_homogenized = false;
};

// OUT.inp -> OUT-stiffness.json (--homogenize).
std::string stiffness_path(const std::string& output) {
  const std::size_t dot = output.find_last_of('.');
  const std::size_t slash = output.find_last_of('/');
  const bool has_extension =
      dot != std::string::npos && (slash == std::string::npos || dot > slash);
  return (has_extension ? output.substr(0, dot) : output) + "-stiffness.json";
}

// Runs CalculiX on the periodic mesh's six load cases and writes OUT-stiffness.json.
void homogenize(const MesomodelFlags& flags, const MesoMesh& mesh, const ProgressStyle style,
                const Overwrite overwrite) {
  const std::string json = stiffness_path(flags.output);
  Homogenized result;
  {
    StageTimer timer("CalculiX, six load cases", style, {.item = "load case", .items_total = 6});
    result = homogenize_with_calculix(
        mesh, flags.file, {.threads = flags.threads, .progress = [&timer](int finished) {
                             timer.set_items(static_cast<std::uint64_t>(finished), 6);
                           }});
  }
  write_stiffness_json(json, result, mesh, flags.file.materials, overwrite);
  for (const std::string& warning : result.warnings) {
    fmt::print(stderr, "aggpack: warning: CalculiX: {}\n", warning);
  }
  const VoigtStiffness& c = result.stiffness;
  fmt::print(
      "stiffness     GPa (Voigt order 11 22 33 23 13 12, engineering shear), asymmetry {:.2e}\n",
      result.asymmetry);
  for (const auto& row : c) {
    fmt::print("             ");
    for (const double value : row) fmt::print(" {:9.4f}", value * 1e-9);
    fmt::print("\n");
  }
  const HashinShtrikmanBounds bounds = hashin_shtrikman_bounds(mesh, flags.file.materials);
  fmt::print(
      "isotropic     E {:.5g} Pa, nu {:.4f} (projection); Hashin-Shtrikman E {:.5g} to {:.5g} Pa\n",
      result.isotropic.youngs, result.isotropic.poisson, bounds.lower.youngs, bounds.upper.youngs);
  fmt::print("wrote {} (CalculiX {} s wall, {} s CPU, {} threads)\n", json,
             format_seconds(result.wall_seconds), format_seconds(result.cpu_seconds),
             result.threads);
}

// --material NAME=E,NU,RHO (Pa, -, kg/m^3) for aggregate, itz or mortar.
void apply_material(const std::string& text, MesoMaterials& materials) {
  const auto equals = text.find('=');
  const std::string name = text.substr(0, equals);
  PhaseMaterial* material = name == "aggregate" ? &materials.aggregate
                            : name == "itz"     ? &materials.itz
                            : name == "mortar"  ? &materials.mortar
                                                : nullptr;
  std::istringstream values(equals == std::string::npos ? "" : text.substr(equals + 1));
  double e = 0;
  double nu = 0;
  double rho = 0;
  char comma1 = 0;
  char comma2 = 0;
  if (material == nullptr || !(values >> e >> comma1 >> nu >> comma2 >> rho) || comma1 != ',' ||
      comma2 != ',' || !values.eof()) {
    throw InvalidInput("--material", text,
                       "NAME=E,NU,RHO with NAME aggregate, itz or mortar (Pa, -, kg/m^3), e.g. "
                       "itz=15e9,0.2,2000");
  }
  *material = {.youngs_modulus = e, .poisson_ratio = nu, .density = rho};
}

void run_voxels(const MesomodelFlags& flags, const Overwrite overwrite) {
  if (flags.resolution < 2 || flags.resolution > 4096) {
    throw InvalidInput("--voxels", std::to_string(flags.resolution), "[2, 4096]");
  }
  VoxelOptions options;
  options.resolution = static_cast<std::uint32_t>(flags.resolution);
  options.itz_thickness = flags.itz;
  const bool is_vti = flags.output.ends_with(".vti");
  if (!is_vti && !flags.output.ends_with(".raw")) {
    throw InvalidInput("-o/--output", aggpack::quoted(flags.output),
                       "a name ending in .vti or .raw with --voxels");
  }
  const std::string base = is_vti ? flags.output : flags.output.substr(0, flags.output.size() - 4);
  if (is_vti) {
    check_writable(flags.output, overwrite);
  } else {
    for (const char* suffix : {".phase.raw", ".particle.raw", ".json"}) {
      check_writable(base + suffix, overwrite);
    }
  }
  const ProgressStyle style = parse_progress_style("--progress", flags.progress);
  const auto start = std::chrono::steady_clock::now();
  const Packing packing = read_packing(flags.input);
  // At most resolution^3 voxels (the longest side has `resolution`).
  const RunEstimate estimate =
      estimate_mesomodel(static_cast<double>(packing.particles.size()),
                         std::pow(static_cast<double>(options.resolution), 3));
  announce_heavy_run(estimate);
  VoxelImage image;  // voxelize checks the ITZ against the container; its messages name the flags
  {
    // voxelize reports nothing while it runs: show the time taken and the estimate's ETA.
    StageTimer timer("voxelising", style, {.expected_seconds = estimate.seconds});
    with_key_names({}, {{"itz_thickness", "--itz"}, {"voxels", "--voxels"}},
                   [&] { image = voxelize(packing, options); });
  }
  if (is_vti) {
    write_vti(flags.output, image, overwrite);
  } else {
    write_voxel_raw(base, image, packing, flags.itz, overwrite);
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const auto counts = image.phase_counts();
  const auto inside = static_cast<double>(counts[0] + counts[1] + counts[2]);
  fmt::print("voxels        {} x {} x {} = {}, side {:.6g} m\n", image.dims[0], image.dims[1],
             image.dims[2], image.count(), image.spacing);
  fmt::print("fractions     aggregate {:.4f}, itz {:.4f}, mortar {:.4f} (of {} voxels inside)\n",
             counts[2] / inside, counts[1] / inside, counts[0] / inside,
             counts[0] + counts[1] + counts[2]);
  fmt::print("wrote {} in {} s\n",
             is_vti ? flags.output : base + ".phase.raw, .particle.raw, .json",
             format_seconds(seconds));
}

void print_report(const MesoMesh& mesh, const MesoReport& report) {
  fmt::print("mesomodel     {} aggregates, ITZ {:.6g} m, container {:.6g} m^3 ({})\n",
             mesh.particle_count, mesh.itz_thickness, report.container_volume,
             prism_summary(mesh.container, mesh.prism_sides));
  fmt::print("mesh          {} nodes, {} tetrahedra; TetGen -{} in {} s{}\n", mesh.nodes.size(),
             mesh.tetrahedra.size(), report.tetgen_switches, format_seconds(report.mesh_seconds),
             report.relabelled_tetrahedra == 0
                 ? std::string()
                 : fmt::format("; {} tetrahedra relabelled by the geometric phase check",
                               report.relabelled_tetrahedra));
  fmt::print("{:<10} {:>11} {:>10} {:>14} {:>14} {:>10} {:>9} {:>9} {:>10} {:>9}\n", "phase",
             "tetrahedra", "nodes", "volume m^3", "exact m^3", "rel.err", "fraction", "min dih.",
             "max aspect", "< 10 deg");
  for (const MesoPhase phase : {MesoPhase::kAggregate, MesoPhase::kItz, MesoPhase::kMortar}) {
    const MesoPhaseReport& p = report.phases[static_cast<int>(phase)];
    const double error = p.expected_volume > 0.0
                             ? (p.meshed_volume - p.expected_volume) / p.expected_volume
                             : p.meshed_volume;
    fmt::print(
        "{:<10} {:>11} {:>10} {:>14.8g} {:>14.8g} {:>10.2e} {:>9.5f} {:>9.3f} {:>10.4g} {:>9}\n",
        phase_set_name(phase), p.quality.tetrahedra, p.nodes, p.meshed_volume, p.expected_volume,
        error, p.meshed_volume / report.container_volume,
        p.quality.tetrahedra > 0 ? p.quality.min_dihedral_degrees : 0.0, p.quality.max_aspect_ratio,
        p.quality.below_10_degrees);
  }
  print_verdict("quality       ", mesomodel_verdict(report));
  if (report.cohesive_elements > 0) {
    const double error =
        (report.interface_area - report.expected_interface_area) / report.expected_interface_area;
    fmt::print(
        "cohesive ITZ  {} COH3D6 elements, area {:.8g} m^2 (exact {:.8g}, rel.err {:.2e}), "
        "constitutive thickness {:.6g} m\n",
        report.cohesive_elements, report.interface_area, report.expected_interface_area, error,
        mesh.itz_thickness);
  }
}

void run_mesh(MesomodelFlags& flags, const Overwrite overwrite) {
  flags.mesh.itz_thickness = flags.itz;
  flags.mesh.itz_kind = flags.itz_kind == "cohesive" ? ItzKind::kCohesive : ItzKind::kSolid;
  // The library names its fields (mesh/mesomodel.h); the messages name the flags typed.
  static const std::map<std::string, std::string> flag_of = {
      {"itz_thickness", "--itz"},
      {"itz_kind", "--itz-kind"},
      {"aggregate_size", "--aggregate-size"},
      {"mortar_size", "--mortar-size"},
      {"radius_edge_ratio", "--radius-edge"},
      {"cylinder_segments", "--cylinder-segments"},
      {"min_dihedral", "--min-dihedral"},
      {"max_aspect_ratio", "--max-aspect"},
      {"time_limit", "--time-limit"}};
  with_key_names({}, flag_of, [&] { validate(flags.mesh); });
  if (flags.file.is_quadratic && flags.mesh.itz_kind == ItzKind::kCohesive) {
    throw InvalidInput("--quadratic", "with --itz-kind cohesive",
                       "linear elements (COH3D6 joins the faces of C3D4, not of C3D10)");
  }
  for (const std::string& text : flags.materials) apply_material(text, flags.file.materials);
  flags.file.has_particle_sets = !flags.has_no_particle_sets;
  flags.file.units = flags.units == "m" ? MesoUnits::kMetre : MesoUnits::kMillimetre;
  flags.file.solver = flags.solver == "iterative" ? MesoSolver::kIterative : MesoSolver::kDirect;
  flags.file.overwrite = overwrite;
  // The file options come from --strain and --material NAME=E,NU,RHO.
  std::map<std::string, std::string> file_flags = {{"step.strain", "--strain"}};
  for (const char* phase : {"aggregate", "itz", "mortar"}) {
    for (const auto& [field, what] : {std::pair<const char*, const char*>{"youngs_modulus", "E"},
                                      {"poisson_ratio", "NU"},
                                      {"density", "RHO"}}) {
      file_flags.emplace(std::string("materials.") + phase + "." + field,
                         std::string("--material ") + phase + " " + what);
    }
  }
  with_key_names({}, file_flags, [&] { validate(flags.file); });
  // Refuse a wrong extension before the work, naming the flag typed.
  try {
    (void)mesomodel_format(flags.output);
  } catch (const InvalidInput&) {
    throw InvalidInput("-o/--output", aggpack::quoted(flags.output),
                       "a name ending in .inp, .msh or .vtu; .vti or .raw with --voxels");
  }
  check_writable(flags.output, overwrite);
  if (flags.is_homogenized) check_writable(stiffness_path(flags.output), overwrite);
  const auto start = std::chrono::steady_clock::now();
  const Packing packing = read_packing(flags.input);
  if (flags.is_homogenized) {  // refused before meshing
    with_key_names({}, {{"homogenize", "--homogenize"}},
                   [&] { (void)check_homogenize(periodic_axes(packing.container)); });
  }
  if (flags.file.is_quadratic && is_periodic(packing.container)) {
    throw InvalidInput("--quadratic", "true with container.periodic",
                       Wording{Sentence::kPeriodicLinear, {}});
  }
  const RunEstimate estimate =
      estimate_mesomodel(static_cast<double>(packing.particles.size()), 0.0);
  announce_heavy_run(estimate);
  MesoReport report;
  const ProgressStyle style = parse_progress_style("--progress", flags.progress);
  MesoMesh mesh;
  {
    // TetGen reports nothing while it meshes (one worker process): show the time it has taken,
    // the estimate's ETA and the time limit.
    StageTimer timer(
        "meshing (TetGen)", style,
        {.limit_seconds = flags.mesh.time_limit, .expected_seconds = estimate.seconds});
    with_key_names({}, flag_of, [&] { mesh = build_mesomodel(packing, flags.mesh, &report); });
  }
  print_report(mesh, report);
  const MesoModulusBounds bounds = voigt_reuss_bounds(mesh, flags.file.materials);
  fmt::print("modulus       Voigt {:.5g} Pa, Reuss {:.5g} Pa ({})\n", bounds.voigt, bounds.reuss,
             mesh.cohesive.empty()
                 ? "bounds of the effective E"
                 : "of aggregate and mortar; the compliant interfaces may go below Reuss");
  const MesoFileSummary summary = write_mesomodel(flags.output, mesh, flags.file);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  fmt::print("wrote {} ({} nodes, {} elements{}) in {} s\n", flags.output, summary.nodes,
             summary.elements,
             is_periodic(packing.container)
                 ? fmt::format(", periodic ties and six load cases of strain {:.6g}",
                               flags.file.step.strain > 0.0 ? flags.file.step.strain : 1e-3)
             : flags.file.step.strain > 0.0
                 ? fmt::format(", compression step to strain {:.6g}", flags.file.step.strain)
                 : std::string(),
             format_seconds(seconds));
  if (flags.is_homogenized) homogenize(flags, mesh, style, overwrite);
}

}  // namespace

void register_mesomodel(CLI::App& app) {
  auto flags = std::make_shared<MesomodelFlags>();
  auto* command = app.add_subcommand(
      "mesomodel",
      "Concrete mesomodel of a packing: the container meshed into aggregate, ITZ and mortar "
      "tetrahedra sharing nodes on every interface, or with --itz-kind cohesive aggregate and "
      "mortar joined by cohesive elements (.inp for Abaqus/CalculiX with sets, materials "
      "and an optional compression step; .msh; .vtu), or with --voxels N the phase image (.vti, "
      "or .raw + .json for FFT solvers). Aggregates must not touch each other or the walls.");
  command->add_option("input", flags->input, "native packing file (.h5)")->required();
  command
      ->add_option("-o,--output", flags->output,
                   "OUT.inp, OUT.msh, OUT.vtu; OUT.vti or OUT.raw with --voxels")
      ->required();
  command
      ->add_option("--itz", flags->itz,
                   "ITZ thickness (m), >= 0; 0 = no ITZ (typical 20-50 um). Solid: a layer of "
                   "tetrahedra this thick over each aggregate, thinned near walls; cohesive: the "
                   "elements' constitutive thickness")
      ->capture_default_str();
  command
      ->add_option("--itz-kind", flags->itz_kind,
                   "solid (a layer of tetrahedra) or cohesive (zero-thickness COH3D6 elements on "
                   "every aggregate surface, for Abaqus; needs --itz > 0)")
      ->check(CLI::IsMember({"solid", "cohesive"}))
      ->capture_default_str();
  command
      ->add_option("--aggregate-size", flags->mesh.aggregate_size,
                   "target tetrahedron edge in the aggregates (m), 0 = no bound")
      ->capture_default_str();
  command
      ->add_option("--mortar-size", flags->mesh.mortar_size,
                   "target tetrahedron edge in the mortar (m), 0 = no bound")
      ->capture_default_str();
  command
      ->add_option("--radius-edge", flags->mesh.radius_edge_ratio,
                   "TetGen's radius-edge quality bound: 0 = none, else [1.2, 10] (may not finish "
                   "with an ITZ)")
      ->capture_default_str();
  command
      ->add_option("--min-dihedral", flags->mesh.min_dihedral_degrees,
                   "refuse a mesh whose smallest dihedral angle is below this (degrees)")
      ->capture_default_str();
  command->add_option("--max-aspect", flags->mesh.max_aspect_ratio,
                      "refuse a mesh whose largest aspect ratio is above this");
  command
      ->add_option("--cylinder-segments", flags->mesh.cylinder_segments,
                   "sides of the prism circumscribing a cylinder container, [8, 4096]")
      ->capture_default_str();
  command->add_option("--time-limit", flags->mesh.time_limit, "seconds TetGen may take")
      ->capture_default_str();
  command
      ->add_option("--strain", flags->file.step.strain,
                   ".inp: add a uniaxial compression step to this nominal strain, [0, 0.1] "
                   "(0 = none)")
      ->capture_default_str();
  command->add_option("--material", flags->materials,
                      ".inp: NAME=E,NU,RHO for aggregate, itz or mortar (Pa, -, kg/m^3); defaults "
                      "60e9,0.2,2700 / 15e9,0.2,2000 / 25e9,0.2,2200");
  command
      ->add_option("--units", flags->units,
                   "length unit of the files: mm (N, MPa, t/mm^3; CalculiX accepts the ITZ's "
                   "thin tetrahedra) or m (SI)")
      ->check(CLI::IsMember({"mm", "m"}))
      ->capture_default_str();
  command
      ->add_option("--solver", flags->solver,
                   ".inp: CalculiX's solver for the steps: direct (SPOOLES, exact) or iterative "
                   "(ITERATIVE CHOLESKY: several times faster on large meshes, off-diagonal "
                   "stiffness terms within ~0.3 %; CalculiX only)")
      ->check(CLI::IsMember({"direct", "iterative"}))
      ->capture_default_str();
  command->add_flag("--quadratic", flags->file.is_quadratic, ".inp: 10-node tetrahedra (C3D10)");
  command->add_flag("--no-particle-sets", flags->has_no_particle_sets,
                    ".inp: leave out the per-particle element sets AGG<k>, ITZ<k>");
  command->add_option("--voxels", flags->resolution,
                      "write the phase image instead: voxels along the longest side, [2, 4096]");
  command->add_option("-j,--threads", flags->threads, "worker threads (0 = all cores)")
      ->capture_default_str();
  command
      ->add_option("--progress", flags->progress,
                   "elapsed time and ETA while TetGen meshes (or the voxels are filled), on "
                   "stderr: auto (redrawn on a terminal, else a line every 2 s), bar, lines, none")
      ->capture_default_str();
  command->add_flag("--homogenize", flags->is_homogenized,
                    "periodic box: run CalculiX (ccx) on the six load cases and write "
                    "OUT-stiffness.json (6x6 tensor in Pa, E and nu of its isotropic projection, "
                    "bounds, solver time)");
  command->add_flag("-f,--force", flags->is_forced, "replace existing output files");
  command->callback([flags, command]() {
    set_thread_count(flags->threads);
    check_output_file_flag("-o/--output", flags->output);
    if (!(flags->itz >= 0.0) || !std::isfinite(flags->itz)) {
      throw InvalidInput("--itz", format_value(flags->itz), ">= 0 (m)");
    }
    const Overwrite overwrite = flags->is_forced ? Overwrite::kAllow : Overwrite::kForbid;
    // Given at all (even --voxels 0) is a voxel run: its range is checked, never ignored.
    if (command->count("--voxels") > 0) {
      if (flags->itz_kind != "solid") {
        throw InvalidInput("--itz-kind", flags->itz_kind,
                           "solid with --voxels (the phase image has no cohesive elements)");
      }
      if (flags->is_homogenized) {
        throw InvalidInput("--homogenize", "with --voxels",
                           "a tetrahedral mesomodel (the phase image is not solved)");
      }
      run_voxels(*flags, overwrite);
    } else {
      run_mesh(*flags, overwrite);
    }
  });
}

}  // namespace aggpack::cli
