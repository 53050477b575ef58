// The homogenised stiffness of a periodic RVE with CalculiX (aggpack/io/homogenize.h).

#include "aggpack/io/homogenize.h"

#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <sstream>

#include "aggpack/core/child_process.h"
#include "aggpack/core/clock.h"
#include "aggpack/core/error.h"
#include "aggpack/core/parallel.h"
#include "aggpack/core/text.h"
#include "aggpack/pack/container.h"

namespace aggpack {

IsotropicModuli isotropic_from_bulk_shear(double bulk, double shear) {
  return {.bulk = bulk,
          .shear = shear,
          .youngs = 9.0 * bulk * shear / (3.0 * bulk + shear),
          .poisson = (3.0 * bulk - 2.0 * shear) / (6.0 * bulk + 2.0 * shear)};
}

VoigtStiffness isotropic_stiffness(double youngs, double poisson) {
  const double lambda = youngs * poisson / ((1.0 + poisson) * (1.0 - 2.0 * poisson));
  const double mu = youngs / (2.0 * (1.0 + poisson));
  VoigtStiffness c{};
  for (std::size_t i = 0; i < 3; ++i) {
    for (std::size_t j = 0; j < 3; ++j) c[i][j] = lambda + (i == j ? 2.0 * mu : 0.0);
    c[i + 3][i + 3] = mu;
  }
  return c;
}

IsotropicModuli isotropic_projection(const VoigtStiffness& c) {
  const double normal = c[0][0] + c[1][1] + c[2][2];
  const double cross = c[0][1] + c[0][2] + c[1][2];
  const double shear = c[3][3] + c[4][4] + c[5][5];
  return isotropic_from_bulk_shear((normal + 2.0 * cross) / 9.0,
                                   (normal - cross + 3.0 * shear) / 15.0);
}

double asymmetry(const VoigtStiffness& c) {
  double largest = 0.0;
  double difference = 0.0;
  for (std::size_t i = 0; i < 6; ++i) {
    for (std::size_t j = 0; j < 6; ++j) {
      largest = std::max(largest, std::abs(c[i][j]));
      difference = std::max(difference, std::abs(c[i][j] - c[j][i]));
    }
  }
  return largest > 0.0 ? difference / largest : 0.0;
}

HashinShtrikmanBounds hashin_shtrikman_bounds(const MesoMesh& mesh,
                                              const MesoMaterials& materials) {
  struct Phase {
    double fraction, bulk, shear;
  };
  const MesoModulusBounds volumes = voigt_reuss_bounds(mesh, materials);
  std::vector<Phase> phases;
  for (const MesoPhase phase : {MesoPhase::kMortar, MesoPhase::kItz, MesoPhase::kAggregate}) {
    const double fraction = volumes.fractions[static_cast<int>(phase)];
    if (fraction <= 0.0) continue;
    const PhaseMaterial& m = materials.of(phase);
    const double nu = m.poisson_ratio;
    phases.push_back({fraction, m.youngs_modulus / (3.0 * (1.0 - 2.0 * nu)),
                      m.youngs_modulus / (2.0 * (1.0 + nu))});
  }
  if (phases.empty()) throw InvalidInput("mesh", "no tetrahedra", "a meshed specimen");
  const auto by_bulk = [](const Phase& a, const Phase& b) { return a.bulk < b.bulk; };
  const auto by_shear = [](const Phase& a, const Phase& b) { return a.shear < b.shear; };
  const double k_min = std::min_element(phases.begin(), phases.end(), by_bulk)->bulk;
  const double k_max = std::max_element(phases.begin(), phases.end(), by_bulk)->bulk;
  const double g_min = std::min_element(phases.begin(), phases.end(), by_shear)->shear;
  const double g_max = std::max_element(phases.begin(), phases.end(), by_shear)->shear;
  // [sum f_i / (m_i + s)]^-1 - s for the phases' modulus m (bulk or shear).
  const auto mix = [&](double Phase::*modulus, double s) {
    double sum = 0.0;
    for (const Phase& p : phases) sum += p.fraction / (p.*modulus + s);
    return 1.0 / sum - s;
  };
  const auto zeta = [](double k, double g) {
    return g * (9.0 * k + 8.0 * g) / (6.0 * (k + 2.0 * g));
  };
  return {.lower = isotropic_from_bulk_shear(mix(&Phase::bulk, 4.0 / 3.0 * g_min),
                                             mix(&Phase::shear, zeta(k_min, g_min))),
          .upper = isotropic_from_bulk_shear(mix(&Phase::bulk, 4.0 / 3.0 * g_max),
                                             mix(&Phase::shear, zeta(k_max, g_max)))};
}

namespace {

std::string trimmed(const std::string& text) {
  const std::size_t first = text.find_first_not_of(" \t\r");
  if (first == std::string::npos) return "";
  return text.substr(first, text.find_last_not_of(" \t\r") + 1 - first);
}

// Load cases ccx has finished: the step lines of its .sta file ("  STEP  INC  ATT ..." header,
// then one line per increment; each load case is one increment).
int finished_steps(const std::string& sta) {
  std::ifstream in(sta);
  std::string line;
  int finished = 0;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    int step = 0;
    if (fields >> step) finished = std::max(finished, step);
  }
  return finished;
}

// ccx's first `limit` messages tagged `tag` ("*WARNING", "*ERROR"): the tagged line and the next
// one that says something (it often says more).
std::vector<std::string> ccx_messages(const std::string& output, const std::string& tag,
                                      std::size_t limit) {
  std::istringstream in(output);
  std::string line;
  std::vector<std::string> messages;
  while (messages.size() < limit && std::getline(in, line)) {
    if (line.find(tag) == std::string::npos) continue;
    std::string next;
    while (std::getline(in, next) && next.find_first_not_of(" \t\r") == std::string::npos) {
    }
    messages.push_back(clipped(trimmed(line) + " " + trimmed(next), 300));
  }
  return messages;
}

// Why ccx failed, from what it printed: its first *ERROR message, else its last line.
std::string ccx_reason(const std::string& output) {
  const std::vector<std::string> errors = ccx_messages(output, "*ERROR", 1);
  if (!errors.empty()) return errors.front();
  std::istringstream in(output);
  std::string line;
  std::string last;
  while (std::getline(in, line)) {
    if (line.find_first_not_of(" \t\r") != std::string::npos) last = line;
  }
  return clipped(last, 300);
}

}  // namespace

std::string check_homogenize(const std::array<bool, 3>& periodic) {
  std::string program = find_on_path("ccx");
  if (program.empty()) {
    throw InvalidInput("homogenize", "true",
                       "with CalculiX installed: no program ccx on PATH (Debian package "
                       "calculix-ccx: apt-get install calculix-ccx)");
  }
  const std::string word = periodic_word(periodic);
  if (word != "xyz") {
    throw InvalidInput("homogenize", "with container.periodic = " + word,
                       "a packing periodic in x, y and z (container.periodic = true)");
  }
  return program;
}

Homogenized homogenize_with_calculix(const MesoMesh& mesh, const MesoFileOptions& options,
                                     const HomogenizeOptions& run) {
  Homogenized result;
  result.program = check_homogenize(mesh.periodic);
  result.solver = options.solver;
  result.threads = run.threads > 0 ? run.threads : allowed_threads();
  result.strain = options.step.strain > 0.0 ? options.step.strain : 1e-3;
  const TemporaryFolder folder("CalculiX");
  MesoFileOptions written = options;
  written.overwrite = Overwrite::kForbid;
  write_mesomodel(folder.file("rve.inp"), mesh, written);
  const auto start = Clock::now();
  std::string output;  // ccx's standard output (its messages; kept for the reason of a failure)
  int status = 0;
  {
    ChildProcess ccx({.program = result.program,
                      .arguments = {"-i", "rve"},
                      .folder = folder.path(),
                      .environment = {"OMP_NUM_THREADS=" + std::to_string(result.threads)},
                      .error_file = folder.file("ccx.err")});
    int reported = -1;
    while (ccx.read_output(output, 200)) {
      if (run.progress) {
        const int finished = finished_steps(folder.file("rve.sta"));
        if (finished != reported) run.progress(reported = finished);
      }
      if (output.size() > (1U << 20U)) output.erase(0, output.size() - (1U << 19U));  // bounded
    }
    status = ccx.wait(result.cpu_seconds);
  }
  result.wall_seconds = seconds_since(start);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 ||
      output.find("Job finished") == std::string::npos) {
    const std::string reason = ccx_reason(output);
    throw IoError("CalculiX (" + result.program + ") failed (" + describe_exit(status) + ")" +
                  (reason.empty() ? std::string() : ": " + reason));
  }
  std::ifstream dat(folder.file("rve.dat"), std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(dat)), std::istreambuf_iterator<char>());
  result.stiffness = periodic_stiffness_from_dat(text, mesh, options);
  result.isotropic = isotropic_projection(result.stiffness);
  result.asymmetry = asymmetry(result.stiffness);
  result.warnings = ccx_messages(output, "*WARNING", 5);
  if (run.progress) run.progress(6);
  return result;
}

namespace {

nlohmann::ordered_json moduli_json(const IsotropicModuli& m) {
  return {{"youngs_modulus_pa", m.youngs},
          {"poisson_ratio", m.poisson},
          {"bulk_modulus_pa", m.bulk},
          {"shear_modulus_pa", m.shear}};
}

}  // namespace

void write_stiffness_json(const std::string& path, const Homogenized& result, const MesoMesh& mesh,
                          const MesoMaterials& materials, Overwrite overwrite) {
  nlohmann::ordered_json json;
  json["stiffness_pa"] = result.stiffness;
  json["voigt_order"] = {"11", "22", "33", "23", "13", "12"};
  json["shear_strain"] = "engineering (gamma = 2 epsilon)";
  json["asymmetry"] = result.asymmetry;
  json["isotropic_projection"] = moduli_json(result.isotropic);
  const MesoModulusBounds averages = voigt_reuss_bounds(mesh, materials);
  const HashinShtrikmanBounds bounds = hashin_shtrikman_bounds(mesh, materials);
  json["bounds"] = {{"voigt_youngs_modulus_pa", averages.voigt},
                    {"reuss_youngs_modulus_pa", averages.reuss},
                    {"hashin_shtrikman_lower", moduli_json(bounds.lower)},
                    {"hashin_shtrikman_upper", moduli_json(bounds.upper)}};
  json["volume_fractions"] = {
      {"aggregate", averages.fractions[static_cast<int>(MesoPhase::kAggregate)]},
      {"itz", averages.fractions[static_cast<int>(MesoPhase::kItz)]},
      {"mortar", averages.fractions[static_cast<int>(MesoPhase::kMortar)]}};
  const auto material_json = [](const PhaseMaterial& m) {
    return nlohmann::ordered_json{{"youngs_modulus_pa", m.youngs_modulus},
                                  {"poisson_ratio", m.poisson_ratio}};
  };
  json["materials"] = {{"aggregate", material_json(materials.aggregate)},
                       {"mortar", material_json(materials.mortar)}};
  const Vec3 extent = mesh.bounds.extent();
  json["rve"] = {{"size_m", {extent.x(), extent.y(), extent.z()}},
                 {"nodes", mesh.nodes.size()},
                 {"tetrahedra", mesh.tetrahedra.size()},
                 {"strain", result.strain}};
  json["solver"] = {
      {"program", result.program},
      {"method", result.solver == MesoSolver::kIterative ? "iterative (ITERATIVE CHOLESKY)"
                                                         : "direct (SPOOLES)"},
      {"threads", result.threads},
      {"wall_seconds", result.wall_seconds},
      {"cpu_seconds", result.cpu_seconds},
      {"warnings", result.warnings}};
  AtomicFile file(path, overwrite);
  file.stream() << json.dump(2) << '\n';
  file.commit();
}

}  // namespace aggpack
