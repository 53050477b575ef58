// The GUI's mesomodel export (issue 16, item 7): the shown packing meshed into aggregate, ITZ and
// mortar (build_mesomodel) and written as .inp, .msh or .vtu (io/mesomodel_files.h), on the
// background job so the window stays live while TetGen works.

#include <fmt/core.h>
#include <imgui.h>

#include <array>
#include <cmath>
#include <string>

#include "aggpack/core/atomic_file.h"
#include "aggpack/core/error.h"
#include "aggpack/io/mesomodel_files.h"
#include "aggpack/mesh/mesomodel.h"
#include "gui_app.h"

namespace aggpack::gui {

void GuiApp::draw_mesomodel_export(bool can_export) {
  ImGui::TextDisabled("Concrete mesomodel (aggregate, ITZ, mortar)");
  ImGui::PushItemWidth(120.0f);
  ImGui::InputDouble("ITZ thickness (mm)", &mesomodel_itz_mm_, 0.01, 0.1, "%.3f");
  ImGui::InputDouble("mortar element (mm)", &mesomodel_mortar_size_mm_, 0.5, 5.0, "%.2f");
  ImGui::PopItemWidth();
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("target element edge in the mortar, 0 = no bound");
  if (!can_export) ImGui::BeginDisabled();
  if (ImGui::Button("Mesomodel (.inp)")) start_mesomodel_export(".inp");
  if (ImGui::IsItemHovered()) {
    ImGui::SetTooltip("mesh the packing (TetGen) and write NAME-mesomodel.inp, .msh or .vtu");
  }
  ImGui::SameLine();
  if (ImGui::Button("(.msh)")) start_mesomodel_export(".msh");
  ImGui::SameLine();
  if (ImGui::Button("(.vtu)")) start_mesomodel_export(".vtu");
  if (!can_export) ImGui::EndDisabled();
}

void GuiApp::start_mesomodel_export(const std::string& extension) {
  if (job_.is_running() || !packing_) return;
  MesoOptions meso;
  meso.itz_thickness = mesomodel_itz_mm_ * 1e-3;
  meso.mortar_size = mesomodel_mortar_size_mm_ * 1e-3;
  try {  // the fields' errors at once, before the job
    if (!(mesomodel_itz_mm_ >= 0.0) || !std::isfinite(mesomodel_itz_mm_)) {
      throw InvalidInput("ITZ thickness (mm)", format_value(mesomodel_itz_mm_), ">= 0");
    }
    if (!(mesomodel_mortar_size_mm_ >= 0.0) || !std::isfinite(mesomodel_mortar_size_mm_)) {
      throw InvalidInput("mortar element (mm)", format_value(mesomodel_mortar_size_mm_),
                         ">= 0 (0 = no bound)");
    }
    validate(meso);
  } catch (const Error& error) {
    set_status(error.what(), true);
    return;
  }
  const std::string path = export_base_ + "-mesomodel" + extension;
  set_status("Meshing the mesomodel for " + path + "...", false);
  job_.start("Meshing mesomodel", [packing = packing_, meso, path](BackgroundJob& job) {
    job.set_detail("TetGen: aggregates and mortar; the ITZ layers");
    MesoReport report;
    const MesoMesh mesh = build_mesomodel(*packing, meso, &report);
    job.set_progress(0.9);
    job.set_detail("writing " + path);
    MesoFileOptions options;
    options.overwrite = Overwrite::kAllow;
    options.units = MesoUnits::kMillimetre;  // as the CLI's default: ccx takes the thin layers
    const MesoFileSummary summary = write_mesomodel(path, mesh, options);
    const double volume = report.container_volume > 0.0 ? report.container_volume : 1.0;
    std::array<double, 3> percent{};
    for (std::size_t p = 0; p < 3; ++p) {
      percent[p] = 100.0 * report.phases[p].meshed_volume / volume;
    }
    JobResult out;
    out.message = fmt::format(
        "Wrote {}: mesomodel of {} aggregates, ITZ {:g} mm, {} nodes, {} tetrahedra (mm, N, MPa); "
        "volume "
        "aggregate {:.1f} %, ITZ {:.1f} %, mortar {:.1f} %.",
        path, mesh.particle_count, mesh.itz_thickness * 1e3, summary.nodes, summary.elements,
        percent[2], percent[1], percent[0]);
    out.is_ok = true;
    return out;
  });
}

}  // namespace aggpack::gui
