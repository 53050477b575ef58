// The GUI's mesomodel export (issue 16, item 7): the shown packing meshed into aggregate, ITZ and
// mortar (build_mesomodel) and written as .inp, .msh or .vtu (io/mesomodel_files.h), on the
// background job so the window stays live while TetGen works.

#include <fmt/core.h>
#include <imgui.h>

#include <array>
#include <cmath>
#include <map>
#include <string>
#include <string_view>

#include "aggpack/core/atomic_file.h"
#include "aggpack/core/error.h"
#include "aggpack/io/mesomodel_files.h"
#include "aggpack/mesh/mesomodel.h"
#include "error_colours.h"
#include "gui_app.h"
#include "i18n.h"
#include "library_words.h"

namespace aggpack::gui {

namespace {

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

// The fields' labels, also the keys of mesomodel_field_errors() ("###" ids: the same widget in
// either language).
const char* itz_field() { return tr(Text::kItzField); }
const char* mortar_field() { return tr(Text::kMortarField); }
const char* kind_field() { return tr(Text::kKindField); }

// A label without its "###id" (as the scripted run prints a field's error).
std::string shown_label(const char* label) {
  const std::string_view text(label);
  return std::string(text.substr(0, text.find("###")));
}

}  // namespace

std::map<std::string, std::string> GuiApp::mesomodel_field_errors() const {
  std::map<std::string, std::string> errors;
  if (!(mesomodel_itz_mm_ >= 0.0) || !std::isfinite(mesomodel_itz_mm_)) {
    errors[shown_label(itz_field())] = trs(Text::kItzNegative, format_value(mesomodel_itz_mm_));
  } else if (mesomodel_itz_kind_ == ItzKind::kCohesive && mesomodel_itz_mm_ == 0.0) {
    errors[shown_label(itz_field())] = tr(Text::kItzCohesiveZero);
  }
  if (!(mesomodel_mortar_size_mm_ >= 0.0) || !std::isfinite(mesomodel_mortar_size_mm_)) {
    errors[shown_label(mortar_field())] =
        trs(Text::kMortarNegative, format_value(mesomodel_mortar_size_mm_));
  }
  return errors;
}

void GuiApp::draw_mesomodel_export(bool can_export) {
  ImGui::TextDisabled("%s", tr(Text::kMesomodelTitle));
  const auto errors = mesomodel_field_errors();
  ImGui::PushItemWidth(150.0f);
  int kind = mesomodel_itz_kind_ == ItzKind::kCohesive ? 1 : 0;
  const char* kinds[] = {tr(Text::kItzSolid), tr(Text::kItzCohesive)};
  ImGui::SetNextItemWidth(200.0f);
  if (ImGui::Combo(kind_field(), &kind, kinds, 2)) {
    mesomodel_itz_kind_ = kind == 1 ? ItzKind::kCohesive : ItzKind::kSolid;
  }
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", tr(Text::kItzKindTooltip));
  ImGui::InputDouble(itz_field(), &mesomodel_itz_mm_, 0.01, 0.1, "%.3f");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", tr(Text::kItzTooltip));
  field_error(errors, shown_label(itz_field()));
  ImGui::InputDouble(mortar_field(), &mesomodel_mortar_size_mm_, 0.5, 5.0, "%.2f");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", tr(Text::kMortarTooltip));
  field_error(errors, shown_label(mortar_field()));
  ImGui::PopItemWidth();
  ImGui::BeginDisabled(!can_export || !errors.empty());
  if (ImGui::Button(tr(Text::kMesomodelInp))) start_mesomodel_export(".inp");
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) {
    ImGui::SetTooltip("%s", tr(Text::kMesomodelInpTooltip));
  }
  ImGui::SameLine();
  if (ImGui::Button(tr(Text::kMesomodelMsh))) start_mesomodel_export(".msh");
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) {
    ImGui::SetTooltip("%s", tr(Text::kMesomodelMshTooltip));
  }
  ImGui::SameLine();
  if (ImGui::Button(tr(Text::kMesomodelVtu))) start_mesomodel_export(".vtu");
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) {
    ImGui::SetTooltip("%s", tr(Text::kMesomodelVtuTooltip));
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
    set_status(error_words(error), true);
    return;
  }
  const std::string path = export_base_ + "-mesomodel" + extension;
  set_status(trs(Text::kStatusMeshing, path), false);
  job_.start(tr(Text::kJobMeshing), [packing = packing_, meso, path](BackgroundJob& job) {
    job.set_detail(tr(Text::kMeshingDetail));
    MesoReport report;
    const MesoMesh mesh = build_mesomodel(*packing, meso, &report);
    job.set_progress(0.9);
    job.set_detail(trs(Text::kWritingDetail, path));
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
        mesh.cohesive.empty() ? std::string() : trs(Text::kCohesiveCount, mesh.cohesive.size());
    out.message =
        trs(Text::kMesomodelWrote, path, mesh.particle_count, mesh.itz_thickness * 1e3,
            tr(mesh.cohesive.empty() ? Text::kItzSolid : Text::kCohesiveWord), summary.nodes,
            mesh.tetrahedra.size(), cohesive, percent[2], percent[1], percent[0]);
    out.is_ok = true;
    return out;
  });
}

}  // namespace aggpack::gui
