// `aggpack mesomodel`: the concrete mesomodel of a packing (issue 16). So far the phase image:
// `--voxels N` labels aggregate / ITZ / mortar voxels (mesh/voxels.h) and writes .vti, or raw +
// JSON header for FFT solvers. The conforming tetrahedral mesh is not built yet.

#include <fmt/core.h>

#include <chrono>
#include <cmath>
#include <memory>
#include <string>

#include "aggpack/core/atomic_file.h"
#include "aggpack/core/error.h"
#include "aggpack/io/native.h"
#include "aggpack/io/voxel_image.h"
#include "aggpack/mesh/voxels.h"
#include "commands.h"

namespace aggpack::cli {

namespace {

struct MesomodelFlags {
  std::string input;
  std::string output;
  VoxelOptions voxels;
  int resolution = 0;
  int threads = 0;
  bool is_forced = false;
};

}  // namespace

void register_mesomodel(CLI::App& app) {
  auto flags = std::make_shared<MesomodelFlags>();
  auto* command = app.add_subcommand(
      "mesomodel",
      "Concrete mesomodel of a packing: aggregate, ITZ and mortar phases. So far the phase image "
      "(--voxels N): .vti (VTK image data) or .raw (BASE.phase.raw, BASE.particle.raw, BASE.json "
      "for FFT solvers). The conforming tetrahedral mesh is not built yet.");
  command->add_option("input", flags->input, "native packing file (.h5)")->required();
  command->add_option("-o,--output", flags->output, "OUT.vti or OUT.raw")->required();
  command->add_option("--voxels", flags->resolution,
                      "voxels along the container's longest side, [2, 4096] (cubic voxels)");
  command
      ->add_option("--itz", flags->voxels.itz_thickness,
                   "ITZ thickness (m), >= 0; 0 = no ITZ (typical 20-50 um)")
      ->capture_default_str();
  command->add_option("-j,--threads", flags->threads, "worker threads (0 = all cores)")
      ->capture_default_str();
  command->add_flag("-f,--force", flags->is_forced, "replace existing output files");
  command->callback([flags]() {
    set_thread_count(flags->threads);
    if (flags->resolution == 0) {
      throw InvalidInput("--voxels", "missing",
                         "a voxel count in [2, 4096] (the tetrahedral mesomodel is not built yet)");
    }
    if (flags->resolution < 2 || flags->resolution > 4096) {
      throw InvalidInput("--voxels", std::to_string(flags->resolution), "[2, 4096]");
    }
    flags->voxels.resolution = static_cast<std::uint32_t>(flags->resolution);
    if (!(flags->voxels.itz_thickness >= 0.0) || !std::isfinite(flags->voxels.itz_thickness)) {
      throw InvalidInput("--itz", format_value(flags->voxels.itz_thickness), ">= 0 (m)");
    }
    const bool is_vti = flags->output.ends_with(".vti");
    if (!is_vti && !flags->output.ends_with(".raw")) {
      throw InvalidInput("--output", flags->output, "a name ending in .vti or .raw");
    }
    const Overwrite overwrite = flags->is_forced ? Overwrite::kAllow : Overwrite::kForbid;
    const std::string base =
        is_vti ? flags->output : flags->output.substr(0, flags->output.size() - 4);
    if (is_vti) {
      check_writable(flags->output, overwrite);
    } else {
      for (const char* suffix : {".phase.raw", ".particle.raw", ".json"}) {
        check_writable(base + suffix, overwrite);
      }
    }
    const auto start = std::chrono::steady_clock::now();
    const Packing packing = read_packing(flags->input);
    const double half_side = 0.5 * packing.container.bounds().extent().minCoeff();
    if (flags->voxels.itz_thickness >= half_side) {
      throw InvalidInput(
          "--itz", format_value(flags->voxels.itz_thickness),
          "[0, " + format_value(half_side) + ") m: half the container's smallest side");
    }
    const VoxelImage image = voxelize(packing, flags->voxels);
    if (is_vti) {
      write_vti(flags->output, image, overwrite);
    } else {
      write_voxel_raw(base, image, packing, flags->voxels.itz_thickness, overwrite);
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
    fmt::print("wrote {} in {:.2f} s\n",
               is_vti ? flags->output : base + ".phase.raw, .particle.raw, .json", seconds);
  });
}

}  // namespace aggpack::cli
