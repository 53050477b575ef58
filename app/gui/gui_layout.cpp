// aggpack-gui's frame around the panel: the menu bar (every action, with its shortcut), the
// status bar at the bottom (a fixed height, so nothing above it moves as the text changes), the
// Help window, keyboard shortcuts, and the 3D view's overlays (axes triad, scale bar).

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <fmt/core.h>
#include <imgui.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include "aggpack/io/export.h"
#include "gui_app.h"
#include "gui_fonts.h"
#include "i18n.h"

namespace aggpack::gui {

namespace {

// The shortcuts, as the Help window and the menus list them.
// (A key's name, or its Text when the name is words; the action.)
struct Shortcut {
  const char* key;
  Text key_words;
  Text action;
};
constexpr std::array<Shortcut, 12> kShortcuts = {{
    {"Enter", Text::kCount, Text::kShortcutPack},
    {"Esc", Text::kCount, Text::kShortcutCancel},
    {"Ctrl+O", Text::kCount, Text::kShortcutOpen},
    {"Ctrl+S", Text::kCount, Text::kShortcutExport},
    {"Ctrl+E", Text::kCount, Text::kShortcutRockDat},
    {"R", Text::kCount, Text::kShortcutReset},
    {"F12", Text::kCount, Text::kShortcutScreenshot},
    {"F1", Text::kCount, Text::kShortcutHelp},
    {nullptr, Text::kKeyLeftDrag, Text::kShortcutRotate},
    {nullptr, Text::kKeyRightDrag, Text::kShortcutPan},
    {nullptr, Text::kKeyWheel, Text::kShortcutZoom},
    {"Ctrl+Q", Text::kCount, Text::kShortcutQuit},
}};

// 1, 2 or 5 times a power of ten, the largest not above `value` (> 0).
double nice_length(double value) {
  const double power = std::pow(10.0, std::floor(std::log10(value)));
  for (double step : {5.0, 2.0, 1.0}) {
    if (step * power <= value) return step * power;
  }
  return power;
}

}  // namespace

void GuiApp::draw_menu_bar() {
  if (!ImGui::BeginMainMenuBar()) return;
  menu_height_ = ImGui::GetWindowSize().y;
  const bool is_idle = !job_.is_running();
  const bool can_export = is_idle && packing_ != nullptr && !upload_.is_pending();
  if (ImGui::BeginMenu(tr(Text::kMenuFile))) {
    if (ImGui::MenuItem(tr(Text::kMenuOpen), "Ctrl+O", false, is_idle)) {
      open_dialog(FileDialog::Kind::kOpen);
    }
    if (ImGui::MenuItem(tr(Text::kMenuExport), "Ctrl+S", false, can_export)) {
      open_dialog(FileDialog::Kind::kExport);
    }
    if (ImGui::MenuItem(tr(Text::kMenuExportRockDat), "Ctrl+E", false, can_export)) {
      open_dialog(FileDialog::Kind::kExport, "dat");
    }
    if (ImGui::BeginMenu(tr(Text::kMenuExportAs), can_export)) {
      for (const FormatInfo& info : export_formats()) {
        // The formats' titles are their programs' names ("Abaqus .inp"), the native one's words.
        const std::string title =
            info.name == "h5" ? std::string(tr(Text::kNativeFormat)) : std::string(info.title);
        if (ImGui::MenuItem(title.c_str())) {
          open_dialog(FileDialog::Kind::kExport, std::string(info.name));
        }
      }
      ImGui::EndMenu();
    }
    if (ImGui::BeginMenu(tr(Text::kMenuExportDeck), can_export)) {
      for (const DeckInfo& deck : deck_kinds()) {
        if (ImGui::MenuItem(deck_title(deck.kind).c_str())) {
          open_dialog(FileDialog::Kind::kExport, format_name(deck.format), deck.kind);
        }
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", deck_run_hint(deck.kind));
      }
      ImGui::EndMenu();
    }
    if (ImGui::BeginMenu(tr(Text::kMenuExportMesomodel), can_export)) {
      for (const char* extension : {".inp", ".msh", ".vtu"}) {
        if (ImGui::MenuItem(extension)) start_mesomodel_export(extension);
      }
      ImGui::EndMenu();
    }
    ImGui::Separator();
    if (ImGui::MenuItem(tr(Text::kMenuScreenshot), "F12")) is_screenshot_requested_ = true;
    if (ImGui::MenuItem(tr(Text::kMenuQuit), "Ctrl+Q")) should_quit_ = true;
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu(tr(Text::kMenuPack))) {
    if (ImGui::MenuItem(tr(Text::kMenuPackNow), "Enter", false, is_idle)) start_pack();
    if (ImGui::MenuItem(tr(Text::kMenuCancel), "Esc", false, !is_idle)) job_.request_cancel();
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu(tr(Text::kMenuView))) {
    if (ImGui::MenuItem(tr(Text::kMenuResetView), "R")) reset_view();
    if (ImGui::MenuItem(tr(Text::kMenuContainer), nullptr, &style_.show_container)) {
      is_scene_dirty_ = true;
    }
    ImGui::MenuItem(tr(Text::kMenuFrameRate), nullptr, &show_fps_);
    draw_language_menu();
    ImGui::EndMenu();
  }
  if (ImGui::BeginMenu(tr(Text::kMenuHelp))) {
    if (ImGui::MenuItem(tr(Text::kMenuShortcuts), "F1")) show_help_ = true;
    ImGui::EndMenu();
  }
  ImGui::EndMainMenuBar();
}

void GuiApp::draw_language_menu() {
  if (!ImGui::BeginMenu(tr(Text::kMenuLanguage))) return;
  const Language now = language();
  if (ImGui::MenuItem(tr(Text::kLanguageEnglish), nullptr, now == Language::kEnglish)) {
    settings_.language = language_code(Language::kEnglish);
    set_gui_language(Language::kEnglish);
  }
  if (ImGui::MenuItem(tr(Text::kLanguageChinese), nullptr, now == Language::kChinese,
                      has_chinese_font())) {
    settings_.language = language_code(Language::kChinese);
    set_gui_language(Language::kChinese);
  }
  if (!has_chinese_font() && ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) {
    ImGui::SetTooltip("%s", tr(Text::kNoChineseFont));
  }
  ImGui::EndMenu();
}

void GuiApp::choose_language() {
  const Language wanted = parse_language(settings_.language).value_or(language_from_environment());
  if (wanted == Language::kChinese && !has_chinese_font()) {
    set_gui_language(Language::kEnglish);
    std::fprintf(stderr, "aggpack-gui: %s\n", tr(Text::kNoChineseFont));
    set_status(tr(Text::kNoChineseFont), false);
    return;
  }
  set_gui_language(wanted);
}

void GuiApp::set_gui_language(Language language) {
  const bool is_start_status = status_.empty() ||
                               status_ == catalogue_text(Language::kEnglish, Text::kStatusStart) ||
                               status_ == catalogue_text(Language::kChinese, Text::kStatusStart);
  set_language(language);
  use_font_of(language);
  if (is_start_status) set_status(tr(Text::kStatusStart), false);
  key_labels_.clear();    // the panel's labels in the new language, made on the next frame
  last_entries_.clear();  // and the fields' errors
}

void GuiApp::draw_help_window() {
  if (!show_help_) return;
  ImGui::SetNextWindowSize(ImVec2(460.0f, 0.0f), ImGuiCond_Appearing);
  ImGui::SetNextWindowPos(ImGui::GetMainViewport()->GetCenter(), ImGuiCond_Appearing,
                          ImVec2(0.5f, 0.5f));
  if (ImGui::Begin(tr(Text::kHelpTitle), &show_help_, ImGuiWindowFlags_NoCollapse)) {
    if (ImGui::BeginTable("##shortcuts", 2, ImGuiTableFlags_RowBg)) {
      ImGui::TableSetupColumn("##key", ImGuiTableColumnFlags_WidthFixed, 90.0f);
      ImGui::TableSetupColumn("##action");
      for (const Shortcut& shortcut : kShortcuts) {
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(shortcut.key != nullptr ? shortcut.key : tr(shortcut.key_words));
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(tr(shortcut.action));
      }
      ImGui::EndTable();
    }
    ImGui::TextWrapped("%s", tr(Text::kHelpText));
  }
  ImGui::End();
}

void GuiApp::draw_status_bar() {
  int width = 0, height = 0;
  glfwGetWindowSize(window_, &width, &height);
  const ImGuiStyle& style = ImGui::GetStyle();
  // Three lines of text, always: the panel and the view above never move.
  status_height_ = 3.0f * ImGui::GetTextLineHeightWithSpacing() + 2.0f * style.WindowPadding.y;
  ImGui::SetNextWindowPos(ImVec2(0.0f, static_cast<float>(height) - status_height_));
  ImGui::SetNextWindowSize(ImVec2(static_cast<float>(width), status_height_));
  constexpr ImGuiWindowFlags kFlags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove |
                                      ImGuiWindowFlags_NoSavedSettings |
                                      ImGuiWindowFlags_NoBringToFrontOnFocus;
  ImGui::Begin("##status", nullptr, kFlags);
  const float fps_width = show_fps_ ? 170.0f : 0.0f;
  ImGui::BeginChild("##status_text", ImVec2(-fps_width, 0.0f), false);
  if (is_status_error_) ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0.95f, 0.35f, 0.3f, 1.0f));
  ImGui::TextWrapped("%s", status_.c_str());
  if (is_status_error_) ImGui::PopStyleColor();
  ImGui::EndChild();
  if (ImGui::IsItemHovered() && !status_.empty()) ImGui::SetTooltip("%s", status_.c_str());
  if (show_fps_) {
    ImGui::SameLine();
    ImGui::BeginGroup();
    ImGui::TextDisabled("%s", trf(Text::kFramesPerSecond, ImGui::GetIO().Framerate).c_str());
    ImGui::TextDisabled("%s", trf(Text::kSceneMilliseconds, 1e3 * last_scene_seconds_).c_str());
    ImGui::EndGroup();
  }
  ImGui::End();
}

void GuiApp::draw_view_overlays() {
  int width = 0, height = 0;
  glfwGetWindowSize(window_, &width, &height);
  const auto left = static_cast<float>(panel_width());
  const float top = menu_height_;
  const float bottom = static_cast<float>(height) - status_height_;
  if (bottom - top < 80.0f || static_cast<float>(width) - left < 120.0f) return;
  ImDrawList* draw = ImGui::GetBackgroundDrawList();
  // Axes triad, lower left: the world axes turned as the view is.
  const Eigen::Matrix4f view = camera_.view_matrix();
  const ImVec2 origin(left + 48.0f, bottom - 48.0f);
  constexpr float kLength = 34.0f;
  draw->AddCircleFilled(origin, 44.0f, IM_COL32(255, 255, 255, 150));
  const std::array<ImU32, 3> colours = {IM_COL32(210, 40, 40, 255), IM_COL32(30, 150, 40, 255),
                                        IM_COL32(40, 80, 220, 255)};
  const std::array<const char*, 3> names = {"x", "y", "z"};
  std::array<int, 3> order = {0, 1, 2};
  // Farther axes first, so the nearer ones are drawn over them.
  std::sort(order.begin(), order.end(), [&](int a, int b) { return view(2, a) < view(2, b); });
  for (int axis : order) {
    const ImVec2 tip(origin.x + kLength * view(0, axis), origin.y - kLength * view(1, axis));
    draw->AddLine(origin, tip, colours[static_cast<std::size_t>(axis)], 2.5f);
    draw->AddText(ImVec2(tip.x + 3.0f * view(0, axis) - 3.0f, tip.y - 3.0f * view(1, axis) - 7.0f),
                  colours[static_cast<std::size_t>(axis)], names[static_cast<std::size_t>(axis)]);
  }
  // Scale bar, lower right: a round length at the depth of the view's centre (the target).
  const double metres_to_pixels = camera_.pixels_per_metre(
      camera_.is_orthographic() ? 1.0 : camera_.distance(), static_cast<int>(bottom - top));
  if (!(metres_to_pixels > 0.0) || !std::isfinite(metres_to_pixels)) return;
  const double length = nice_length(140.0 / metres_to_pixels);
  const auto pixels = static_cast<float>(length * metres_to_pixels);
  const float right = static_cast<float>(width) - 24.0f;
  const float y = bottom - 22.0f;
  const ImU32 ink = IM_COL32(30, 32, 38, 255);
  const std::string label = length >= 1.0    ? fmt::format("{:g} m", length)
                            : length >= 1e-3 ? fmt::format("{:g} mm", length * 1e3)
                                             : fmt::format("{:g} um", length * 1e6);
  draw->AddRectFilled(ImVec2(right - pixels - 8.0f, y - 22.0f), ImVec2(right + 8.0f, y + 8.0f),
                      IM_COL32(255, 255, 255, 150), 4.0f);
  draw->AddLine(ImVec2(right - pixels, y), ImVec2(right, y), ink, 3.0f);
  draw->AddLine(ImVec2(right - pixels, y - 5.0f), ImVec2(right - pixels, y + 5.0f), ink, 2.0f);
  draw->AddLine(ImVec2(right, y - 5.0f), ImVec2(right, y + 5.0f), ink, 2.0f);
  const ImVec2 text = ImGui::CalcTextSize(label.c_str());
  draw->AddText(ImVec2(right - 0.5f * (pixels + text.x), y - 20.0f), ink, label.c_str());
}

void GuiApp::on_key(int key, int action, int mods) {
  if (action != GLFW_PRESS) return;
  const bool is_ctrl = (mods & GLFW_MOD_CONTROL) != 0;
  if (is_ctrl) {
    if (key == GLFW_KEY_O) open_dialog(FileDialog::Kind::kOpen);
    if (key == GLFW_KEY_S) open_dialog(FileDialog::Kind::kExport);
    if (key == GLFW_KEY_E) open_dialog(FileDialog::Kind::kExport, "dat");
    if (key == GLFW_KEY_Q) should_quit_ = true;
    return;
  }
  if (key == GLFW_KEY_F12) is_screenshot_requested_ = true;
  if (ImGui::GetIO().WantTextInput || dialog_.kind != FileDialog::Kind::kNone) return;
  if (key == GLFW_KEY_F1) show_help_ = true;
  if (key == GLFW_KEY_R) reset_view();
  if (key == GLFW_KEY_ENTER || key == GLFW_KEY_KP_ENTER) start_pack();
  if (key == GLFW_KEY_ESCAPE && job_.is_running()) job_.request_cancel();
}

}  // namespace aggpack::gui
