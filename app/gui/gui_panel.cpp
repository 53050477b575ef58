// The panel's own sections around the configuration: Pack / Cancel with the job's progress and
// the result's state, Open and Export, and the view's settings with its colour legend.

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <fmt/core.h>
#include <imgui.h>

#include <array>
#include <cmath>
#include <string>
#include <utility>

#include "gui_app.h"
#include "i18n.h"

namespace aggpack::gui {

namespace {

// The last item's tooltip.
void item_tooltip(const char* text) {
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", text);
}

// Colour bar for the scale colour modes.
void draw_legend(const ParticleColors& colors, ColorMode mode) {
  ImDrawList* draw = ImGui::GetWindowDrawList();
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  const float width = ImGui::GetContentRegionAvail().x;
  const float height = 12.0f;
  constexpr int kSteps = 48;
  for (int k = 0; k < kSteps; ++k) {
    const Rgb c = scale_color((k + 0.5) / kSteps);
    const float x0 = origin.x + width * static_cast<float>(k) / kSteps;
    const float x1 = origin.x + width * static_cast<float>(k + 1) / kSteps;
    draw->AddRectFilled(ImVec2(x0, origin.y), ImVec2(x1, origin.y + height),
                        IM_COL32(c.r, c.g, c.b, 255));
  }
  ImGui::Dummy(ImVec2(width, height));
  ImGui::Text("%.4g", colors.minimum);
  ImGui::SameLine(width - ImGui::CalcTextSize(fmt::format("{:.4g}", colors.maximum).c_str()).x);
  ImGui::Text("%.4g", colors.maximum);
  ImGui::TextDisabled("%s", tr(mode == ColorMode::kSize ? Text::kLegendSize : Text::kLegendAlpha));
}

// "ETA 12 s" from the time taken so far and the fraction done ("" too early to say).
std::string eta_text(double elapsed, double fraction) {
  if (fraction < 0.02 || elapsed < 1.0 || fraction >= 1.0) return "";
  const double left = elapsed * (1.0 - fraction) / fraction;
  if (left < 60.0) return trs(Text::kEtaSeconds, left);
  return trs(Text::kEtaMinutes, std::floor(left / 60.0), std::fmod(left, 60.0));
}

}  // namespace

void GuiApp::draw_panel() {
  int width = 0, height = 0;
  glfwGetWindowSize(window_, &width, &height);
  ImGui::SetNextWindowPos(ImVec2(0, menu_height_));
  ImGui::SetNextWindowSize(
      ImVec2(static_cast<float>(panel_width()),
             std::max(1.0f, static_cast<float>(height) - menu_height_ - status_height_)));
  ImGui::Begin("###panel", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                   ImGuiWindowFlags_NoTitleBar | ImGuiWindowFlags_NoSavedSettings);
  // Pack / Cancel, the progress and the result's state first, in a fixed height: always in view
  // and never moving what is below; the sections scroll beneath it.
  draw_job_section();
  ImGui::BeginChild("##sections", ImVec2(0.0f, 0.0f), false);
  ImGui::PushItemWidth(-150.0f);
  draw_config_section(tr(Text::kSectionContainer), {"container"});
  draw_config_section(tr(Text::kSectionParticle), {"particle"});
  draw_config_section(tr(Text::kSectionPacker), {"packer", "grading", "densify"});
  ImGui::PopItemWidth();
  if (!form_error_.empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0.95f, 0.35f, 0.3f, 1.0f));
    ImGui::TextWrapped("%s", form_error_.c_str());
    ImGui::PopStyleColor();
  }
  draw_file_section();
  draw_view_section();
  ImGui::EndChild();
  ImGui::End();
}

void GuiApp::draw_job_section() {
  const float line = ImGui::GetFrameHeightWithSpacing();
  ImGui::BeginChild("##job", ImVec2(0.0f, 3.0f * line + 4.0f), false, ImGuiWindowFlags_NoScrollbar);
  const bool is_running = job_.is_running();
  ImGui::BeginDisabled(is_running);
  if (ImGui::Button(tr(Text::kPackButton), ImVec2(120, 0))) start_pack();
  ImGui::EndDisabled();
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) {
    ImGui::SetTooltip("%s", tr(Text::kPackTooltip));
  }
  ImGui::SameLine();
  ImGui::BeginDisabled(!is_running);
  if (ImGui::Button(tr(Text::kCancelButton), ImVec2(-1, 0))) job_.request_cancel();
  ImGui::EndDisabled();
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) {
    ImGui::SetTooltip("%s", tr(Text::kCancelTooltip));
  }
  // The progress bar line: the job, the scene upload, or empty.
  if (is_running) {
    const double fraction = job_.progress();
    const std::string overlay = trs(Text::kProgressOverlay, job_.name(), 100.0 * fraction,
                                    eta_text(job_.elapsed_seconds(), fraction));
    ImGui::ProgressBar(static_cast<float>(fraction), ImVec2(-1, 0), overlay.c_str());
    const std::string detail = job_.detail();
    ImGui::TextUnformatted(detail.c_str());
  } else if (renderer_->is_upload_pending()) {
    const std::string overlay = trs(Text::kShowingPacking, 100.0 * renderer_->upload_progress());
    ImGui::ProgressBar(static_cast<float>(renderer_->upload_progress()), ImVec2(-1, 0),
                       overlay.c_str());
  } else if (is_result_stale()) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.75f, 0.3f, 1.0f));
    ImGui::TextUnformatted(tr(Text::kOutOfDate));
    ImGui::TextUnformatted(tr(Text::kPackAgain));
    ImGui::PopStyleColor();
    if (ImGui::IsItemHovered()) {
      std::string keys;
      for (const std::string& key : changed_keys()) keys += "\n  " + key;
      ImGui::SetTooltip("%s", trf(Text::kChangedTooltip, keys).c_str());
    }
  } else if (packing_) {
    ImGui::TextDisabled("%s", tr(Text::kResultCurrent));
  }
  ImGui::EndChild();
  ImGui::Separator();
}

void GuiApp::draw_file_section() {
  if (!ImGui::CollapsingHeader(tr(Text::kSectionFiles), ImGuiTreeNodeFlags_DefaultOpen)) return;
  const bool is_idle = !job_.is_running();
  ImGui::BeginDisabled(!is_idle);
  if (ImGui::Button(tr(Text::kOpenButton), ImVec2(110, 0))) open_dialog(FileDialog::Kind::kOpen);
  ImGui::EndDisabled();
  item_tooltip(tr(Text::kOpenTooltip));
  const bool can_export = packing_ != nullptr && is_idle && !upload_.is_pending();
  ImGui::BeginDisabled(!can_export);
  ImGui::SameLine();
  if (ImGui::Button(tr(Text::kExportButton), ImVec2(110, 0))) {
    open_dialog(FileDialog::Kind::kExport);
  }
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) {
    ImGui::SetTooltip("%s", tr(Text::kExportTooltip));
  }
  ImGui::SameLine();
  if (ImGui::Button(tr(Text::kRockDatButton), ImVec2(-1, 0))) {
    open_dialog(FileDialog::Kind::kExport, "dat");
  }
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) {
    ImGui::SetTooltip("%s", tr(Text::kRockDatTooltip));
  }
  ImGui::EndDisabled();
  draw_mesomodel_export(can_export);
}

void GuiApp::draw_view_section() {
  if (!ImGui::CollapsingHeader(tr(Text::kSectionView), ImGuiTreeNodeFlags_DefaultOpen)) return;
  bool is_changed = false;
  int color = static_cast<int>(style_.color);
  ImGui::TextUnformatted(tr(Text::kColourBy));
  ImGui::SameLine();
  is_changed |= ImGui::RadioButton(tr(Text::kColourParticle), &color, 0);
  item_tooltip(tr(Text::kColourParticleTooltip));
  ImGui::SameLine();
  is_changed |= ImGui::RadioButton(tr(Text::kColourSize), &color, 1);
  item_tooltip(tr(Text::kColourSizeTooltip));
  ImGui::SameLine();
  is_changed |= ImGui::RadioButton(tr(Text::kColourAlpha), &color, 2);
  item_tooltip(tr(Text::kColourAlphaTooltip));
  style_.color = static_cast<ColorMode>(color);
  is_changed |= ImGui::Checkbox(tr(Text::kWireframe), &style_.is_wireframe);
  item_tooltip(tr(Text::kWireframeTooltip));
  ImGui::SameLine();
  is_changed |= ImGui::Checkbox(tr(Text::kContainerCheck), &style_.show_container);
  item_tooltip(tr(Text::kContainerTooltip));
  ImGui::SameLine();
  bool is_orthographic = camera_.is_orthographic();
  if (ImGui::Checkbox(tr(Text::kOrtho), &is_orthographic)) {
    camera_.set_orthographic(is_orthographic);
    reset_view();
  }
  item_tooltip(tr(Text::kOrthoTooltip));
  constexpr std::array<std::pair<ViewPreset, Text>, 4> kPresets = {{
      {ViewPreset::kIso, Text::kViewIso},
      {ViewPreset::kFront, Text::kViewFront},
      {ViewPreset::kSide, Text::kViewSide},
      {ViewPreset::kTop, Text::kViewTop},
  }};
  for (std::size_t k = 0; k < kPresets.size(); ++k) {
    if (k > 0) ImGui::SameLine();
    if (ImGui::Button(tr(kPresets[k].second))) {
      view_ = kPresets[k].first;
      reset_view();
    }
    item_tooltip(tr(Text::kViewPresetTooltip));
  }
  ImGui::SameLine();
  if (ImGui::Button(tr(Text::kResetViewButton))) reset_view();
  item_tooltip(tr(Text::kResetViewTooltip));
  float coarse = static_cast<float>(style_.coarse_below_pixels);
  ImGui::SetNextItemWidth(-130.0f);
  if (ImGui::SliderFloat(tr(Text::kCoarseBelow), &coarse, 0.0f, 64.0f, tr(Text::kPixelsFormat),
                         ImGuiSliderFlags_AlwaysClamp)) {
    style_.coarse_below_pixels = coarse;
    is_changed = true;
  }
  item_tooltip(tr(Text::kCoarseTooltip));
  int budget = static_cast<int>(style_.triangle_budget / 1000);
  ImGui::SetNextItemWidth(-130.0f);
  if (ImGui::SliderInt(tr(Text::kTriangleBudget), &budget, 0, 5000,
                       tr(budget == 0 ? Text::kNoLimit : Text::kThousandsFormat),
                       ImGuiSliderFlags_AlwaysClamp)) {
    style_.triangle_budget = static_cast<std::size_t>(budget) * 1000;
    is_scene_dirty_ = true;
  }
  item_tooltip(tr(Text::kTriangleBudgetTooltip));
  if (style_.color != ColorMode::kParticle && renderer_->particle_count() > 0) {
    draw_legend(renderer_->colors(style_.color), style_.color);
  }
  ImGui::PushTextWrapPos(0.0f);
  ImGui::TextDisabled("%s", trf(Text::kStatsShapes, renderer_->particle_count(),
                                renderer_->shape_count(), renderer_->merged_shape_count())
                                .c_str());
  ImGui::TextDisabled("%s", trf(Text::kStatsDrawn, last_stats_.particles_in_frustum,
                                last_stats_.particles_drawn, last_stats_.coarse_particles,
                                last_stats_.point_particles, last_stats_.triangles / 1e6)
                                .c_str());
  if (needs_light_frames_) {
    const DetailLevel level = detail_.level();
    const Formatted particles = level.max_particles == 0
                                    ? trf(Text::kStatsAll)
                                    : trf(Text::kStatsThousands, level.max_particles / 1000);
    ImGui::TextDisabled(
        "%s", trf(Text::kStatsMoving, 1e3 * last_picture_latency_, level.triangle_budget / 1000,
                  100.0 * level.resolution_scale, particles.c_str())
                  .c_str());
  } else {
    ImGui::TextDisabled("%s", trf(Text::kStatsFullDetail, 1e3 * last_picture_latency_).c_str());
  }
  ImGui::PopTextWrapPos();
  if (is_changed) is_scene_dirty_ = true;
}

}  // namespace aggpack::gui