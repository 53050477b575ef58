#pragma once
// Shared helpers of the exporter tests: small packings built directly (random aggregate particles
// on a non-overlapping grid, randomly rotated), a scratch folder, and running external readers.

#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "aggpack/core/rng.h"
#include "aggpack/geom/mass_properties.h"
#include "aggpack/pack/packing.h"
#include "aggpack/shape/generator.h"

namespace aggpack::test {

/// nx * ny * nz particles (radius 0.1 m, alpha 0.5, L = 0.1 m), one shape each, randomly rotated,
/// on a grid of pitch 0.25 m starting at z = 0.1, so no two overlap. Particle i has size class
/// i % 3. With `share_shapes`, particles reuse 3 shapes and odd ones get a library scale 0.8.
/// `growth`: the particles' growth rule.
inline Packing grid_packing(int nx, int ny, int nz, std::uint64_t seed = 1,
                            bool share_shapes = false, Growth growth = Growth::kHull) {
  Packing packing;
  packing.provenance.packer = "test-grid";
  packing.provenance.seed = seed;
  const GeneratorOptions generator{.alpha = 0.5,
                                   .radius_min = 0.1,
                                   .radius_max = 0.1,
                                   .edge_length = 0.1,
                                   .seed = seed,
                                   .form = {.growth = growth}};
  const int count = nx * ny * nz;
  const int shape_count = share_shapes ? std::min(3, count) : count;
  for (int s = 0; s < shape_count; ++s) {
    ConvexPolyhedron body = generate_particle(generator, static_cast<std::uint64_t>(s)).body;
    // Stored shapes have their centroid at the origin (Packing's convention).
    packing.shapes.push_back(body.translated(-mass_properties(body).centroid));
  }
  Rng rng(seed, 99);
  int i = 0;
  for (int z = 0; z < nz; ++z) {
    for (int y = 0; y < ny; ++y) {
      for (int x = 0; x < nx; ++x, ++i) {
        Particle particle;
        particle.shape = static_cast<std::uint32_t>(i % shape_count);
        particle.pose.position = Vec3(0.15 + 0.25 * x, 0.15 + 0.25 * y, 0.15 + 0.25 * z);
        particle.pose.rotation =
            Quat(rng.normal(), rng.normal(), rng.normal(), rng.normal()).normalized();
        particle.control_radius = 0.1;
        particle.size_class = static_cast<std::uint32_t>(i % 3);
        if (share_shapes && i % 2 == 1) particle.scale = 0.8;
        packing.particles.push_back(particle);
      }
    }
  }
  packing.container.get_if<BoxContainer>()->length = 0.3 + 0.25 * nx;
  packing.container.get_if<BoxContainer>()->width = 0.3 + 0.25 * ny;
  packing.container.get_if<BoxContainer>()->depth = 0.3 + 0.25 * nz;
  return packing;
}

/// Volume of particle i of a packing (m^3), from its placed polyhedron.
inline double particle_volume(const Packing& packing, std::size_t i) {
  return mass_properties(packing.placed(i)).volume;
}

/// A fresh folder under the temp directory, removed at the end of the test.
class ScratchFolder {
 public:
  ScratchFolder() {
    std::string pattern = (std::filesystem::temp_directory_path() / "aggpack_export_XXXXXX");
    std::vector<char> buffer(pattern.begin(), pattern.end());
    buffer.push_back('\0');
    if (::mkdtemp(buffer.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
    path_ = buffer.data();
  }
  ~ScratchFolder() {
    std::error_code error;
    std::filesystem::remove_all(path_, error);
  }
  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;
  [[nodiscard]] std::string file(const std::string& name) const { return (path_ / name).string(); }
  [[nodiscard]] const std::filesystem::path& path() const { return path_; }
  /// Names of the entries in the folder (to check that no temporary file is left behind).
  [[nodiscard]] std::vector<std::string> entries() const {
    std::vector<std::string> names;
    for (const auto& entry : std::filesystem::directory_iterator(path_)) {
      names.push_back(entry.path().filename().string());
    }
    std::sort(names.begin(), names.end());
    return names;
  }

 private:
  std::filesystem::path path_;
};

/// Result of a shell command.
struct CommandResult {
  int exit_code = -1;
  std::string output;  ///< stdout and stderr together
};

inline CommandResult run_command(const std::string& command) {
  CommandResult result;
  FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
  if (pipe == nullptr) return result;
  char buffer[4096];
  std::size_t got = 0;
  while ((got = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) result.output.append(buffer, got);
  const int status = ::pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

/// True when `program` is on the PATH (external readers are installed by scripts/install-deps.sh).
inline bool has_program(const std::string& program) {
  return run_command("command -v " + program + " >/dev/null").exit_code == 0;
}

/// Debian's python3 (with python3-meshio and python3-vtk9), not a pyenv/venv one.
inline std::string system_python() { return "/usr/bin/python3"; }

inline bool has_python_module(const std::string& module) {
  return run_command("cd / && " + system_python() + " -c 'import " + module + "'").exit_code == 0;
}

/// Runs a Python script with Debian's python3 and returns its output; the script gets the
/// arguments after it.
inline CommandResult run_python(const ScratchFolder& folder, const std::string& script,
                                const std::string& arguments) {
  const std::string path = folder.file("check.py");
  std::ofstream(path) << script;
  // Run from / so that nothing in the working folder shadows a module.
  return run_command("cd / && " + system_python() + " " + path + " " + arguments);
}

/// Has Gmsh read the mesh file `path` and write it again as MSH 4.1 to `again` (gmsh -0).
/// Succeeds when Gmsh exits with 0, prints no "Error" (nor "Warning" unless `allow_warnings`)
/// and wrote `again`; the failure message holds Gmsh's output.
inline ::testing::AssertionResult gmsh_rewrites(const std::string& path, const std::string& again,
                                                bool allow_warnings) {
  const CommandResult gmsh = run_command("gmsh " + path + " -0 -format msh41 -o " + again);
  if (gmsh.exit_code != 0) {
    return ::testing::AssertionFailure() << "gmsh exit code " << gmsh.exit_code << ":\n"
                                         << gmsh.output;
  }
  if (gmsh.output.find("Error") != std::string::npos) {
    return ::testing::AssertionFailure() << "gmsh reported an error:\n" << gmsh.output;
  }
  if (!allow_warnings && gmsh.output.find("Warning") != std::string::npos) {
    return ::testing::AssertionFailure() << "gmsh warned:\n" << gmsh.output;
  }
  if (!std::filesystem::exists(again)) {
    return ::testing::AssertionFailure() << "gmsh wrote no " << again << ":\n" << gmsh.output;
  }
  return ::testing::AssertionSuccess();
}

inline std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

inline std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::string part;
  std::istringstream stream(text);
  while (std::getline(stream, part, separator)) parts.push_back(part);
  return parts;
}

inline std::string trim(const std::string& text) {
  const auto begin = text.find_first_not_of(" \t\r\n");
  if (begin == std::string::npos) return "";
  const auto end = text.find_last_not_of(" \t\r\n");
  return text.substr(begin, end - begin + 1);
}

/// A Python script (argv[1] = the file) prints `expected` both for the mesh file `path` and for
/// Gmsh's rewrite of it (gmsh_rewrites, no warnings allowed): Gmsh reads the file and loses
/// nothing the script looks at.
inline void expect_same_through_gmsh(const ScratchFolder& folder, const std::string& script,
                                     const std::string& path, const std::string& expected) {
  const CommandResult ours = run_python(folder, script, path);
  ASSERT_EQ(ours.exit_code, 0) << ours.output;
  EXPECT_EQ(trim(ours.output), expected);
  const std::string again = folder.file("again.msh");
  ASSERT_TRUE(gmsh_rewrites(path, again, /*allow_warnings=*/false));
  const CommandResult theirs = run_python(folder, script, again);
  ASSERT_EQ(theirs.exit_code, 0) << theirs.output;
  EXPECT_EQ(trim(theirs.output), expected);
}

}  // namespace aggpack::test
