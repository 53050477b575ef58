// The GUI's mesomodel export (issue 16, item 7): the shown packing meshed into aggregate, ITZ and
// mortar (build_mesomodel) and written as .inp, .msh or .vtu (io/mesomodel_files.h), on the
// background job so the window stays live while TetGen works.

#include <fmt/core.h>
#include <imgui.h>

#include <array>
#include <cmath>
#include <map>
#include <string>

#include "aggpack/core/atomic_file.h"
#include "aggpack/core/error.h"
#include "aggpack/io/mesomodel_files.h"
#include "aggpack/mesh/mesomodel.h"
#include "gui_app.h"

namespace aggpack::gui {

namespace {

const ImVec4 kErrorText(0.95f, 0.35f, 0.3f, 1.0f);

// The plain-words error of a field, right under it (nothing when it is valid).
void field_error(const std::map<std::string, std::string>& errors, const std::string& field) {
  const auto found = errors.find(field);
  if (found == errors.end()) return;
  ImGui::PushStyleColor(ImGuiCol_Text, kErrorText);
  ImGui::PushTextWrapPos(0.0f);
  ImGui::TextUnformatted(found->second.c_str());
  ImGui::PopTextWrapPos();
  ImGui::PopStyleColor();
}

constexpr const char* kItzField = "ITZ thickness (mm)";
constexpr const char* kMortarField = "mortar element (mm)";
constexpr const char* kKindField = "ITZ model";

}  // namespace

std::map<std::string, std::string> GuiApp::mesomodel_field_errors() const {
  std::map<std::string, std::string> errors;
  if (!(mesomodel_itz_mm_ >= 0.0) || !std::isfinite(mesomodel_itz_mm_)) {
    errors[kItzField] = fmt::format("{} mm is not allowed: the ITZ thickness is 0 or more.",
                                    format_value(mesomodel_itz_mm_));
  } else if (mesomodel_itz_kind_ == ItzKind::kCohesive && mesomodel_itz_mm_ == 0.0) {
    errors[kItzField] =
        "Cohesive elements need an ITZ thickness above 0 (their constitutive thickness).";
  }
  if (!(mesomodel_mortar_size_mm_ >= 0.0) || !std::isfinite(mesomodel_mortar_size_mm_)) {
    errors[kMortarField] =
        fmt::format("{} mm is not allowed: the mortar element is 0 (no bound) or more.",
                    format_value(mesomodel_mortar_size_mm_));
  }
  return errors;
}

void GuiApp::draw_mesomodel_export(bool can_export) {
  ImGui::TextDisabled("Concrete mesomodel (aggregate, ITZ, mortar)");
  const auto errors = mesomodel_field_errors();
  ImGui::PushItemWidth(150.0f);
  int kind = mesomodel_itz_kind_ == ItzKind::kCohesive ? 1 : 0;
  const char* kinds[] = {"solid layer", "cohesive elements (Abaqus)"};
  ImGui::SetNextItemWidth(200.0f);
  if (ImGui::Combo(kKindField, &kind, kinds, 2)) {
    mesomodel_itz_kind_ = kind == 1 ? ItzKind::kCohesive : ItzKind::kSolid;
  }
  if (ImGui::IsItemHovered()) {
    ImGui::SetTooltip(
        "How the interfacial transition zone (ITZ) around each aggregate is modelled:\n"
        "solid layer: tetrahedra of the ITZ thickness around every aggregate (0 = none);\n"
        "cohesive elements: zero-thickness COH3D6 wedges on every aggregate-mortar interface\n"
        "(Abaqus; .msh/.vtu get them as prisms/wedges); the thickness is then their\n"
        "constitutive thickness, > 0.");
  }
  field_error(errors, kKindField);
  ImGui::InputDouble(kItzField, &mesomodel_itz_mm_, 0.01, 0.1, "%.3f");
  if (ImGui::IsItemHovered()) {
    ImGui::SetTooltip(
        "ITZ thickness t (mm), >= 0; typical 0.02-0.05. Solid layer: its geometric thickness\n"
        "(the layers of two particles must not meet: pack with a gap); 0 = no ITZ.\n"
        "Cohesive elements: their constitutive thickness, > 0.");
  }
  field_error(errors, kItzField);
  ImGui::InputDouble(kMortarField, &mesomodel_mortar_size_mm_, 0.5, 5.0, "%.2f");
  if (ImGui::IsItemHovered()) {
    ImGui::SetTooltip("target element edge in the aggregates and mortar (mm), 0 = no bound");
  }
  field_error(errors, kMortarField);
  ImGui::PopItemWidth();
  ImGui::BeginDisabled(!can_export || !errors.empty());
  if (ImGui::Button("Mesomodel (.inp)")) start_mesomodel_export(".inp");
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) {
    ImGui::SetTooltip(
        "mesh the packing (TetGen) and write NAME-mesomodel.inp (Abaqus/CalculiX: sets, "
        "materials, a compression step)");
  }
  ImGui::SameLine();
  if (ImGui::Button("(.msh)")) start_mesomodel_export(".msh");
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) {
    ImGui::SetTooltip("mesh the packing (TetGen) and write NAME-mesomodel.msh (Gmsh 4.1)");
  }
  ImGui::SameLine();
  if (ImGui::Button("(.vtu)")) start_mesomodel_export(".vtu");
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) {
    ImGui::SetTooltip("mesh the packing (TetGen) and write NAME-mesomodel.vtu (ParaView)");
  }
  ImGui::EndDisabled();
}

void GuiApp::start_mesomodel_export(const std::string& extension) {
  if (job_.is_running() || !packing_) return;
  MesoOptions meso;
  meso.itz_thickness = mesomodel_itz_mm_ * 1e-3;
  meso.mortar_size = mesomodel_mortar_size_mm_ * 1e-3;
  meso.itz_kind = mesomodel_itz_kind_;
  // The fields' errors at once, before the job, in the words shown next to the fields.
  const auto errors = mesomodel_field_errors();
  if (!errors.empty()) {
    set_status(errors.begin()->first + ": " + errors.begin()->second, true);
    return;
  }
  try {
    validate(meso);
  } catch (const Error& error) {
    set_status(plain_error(error.what()), true);
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
    const std::string cohesive =
        mesh.cohesive.empty()
            ? std::string()
            : fmt::format(" and {} cohesive elements (COH3D6)", mesh.cohesive.size());
    out.message = fmt::format(
        "Wrote {}: mesomodel of {} aggregates, ITZ {:g} mm ({}), {} nodes, {} tetrahedra{} (mm, "
        "N, MPa); volume aggregate {:.1f} %, ITZ {:.1f} %, mortar {:.1f} %.",
        path, mesh.particle_count, mesh.itz_thickness * 1e3,
        mesh.cohesive.empty() ? "solid layer" : "cohesive", summary.nodes, mesh.tetrahedra.size(),
        cohesive, percent[2], percent[1], percent[0]);
    out.is_ok = true;
    return out;
  });
}

}  // namespace aggpack::gui
