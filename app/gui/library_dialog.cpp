// aggpack-gui's shape library dialog (particle.library): browse folders with std::filesystem (no
// file dialog for ImGui is packaged in Debian), then use the shown folder's meshes or the files
// picked in it. The choice fills the panel's particle.library field as a list of paths and
// switches it on; the folder is remembered with the Open and Export dialogs' (gui_settings.h).

#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "file_dialog.h"
#include "gui_app.h"
#include "i18n.h"

namespace aggpack::gui {

namespace fs = std::filesystem;

namespace {

// The folder to start in: the chosen library's (a folder, or a file's folder), else the kept one.
std::string start_folder(const std::vector<std::string>& paths, const std::string& kept) {
  if (paths.empty()) return kept;
  std::error_code code;
  const fs::path first(paths.front());
  if (fs::is_directory(first, code)) return first.string();
  const fs::path parent = first.parent_path();
  return parent.empty() ? kept : parent.string();
}

bool wide_button(const char* label) {
  const float width =
      ImGui::CalcTextSize(label, nullptr, true).x + 2.0f * ImGui::GetStyle().FramePadding.x;
  return ImGui::Button(label, ImVec2(std::max(170.0f, width), 0.0f));
}

}  // namespace

void GuiApp::open_library_dialog(const std::string& folder) {
  if (job_.is_running() || upload_.is_pending()) return;
  dialog_.kind = FileDialog::Kind::kLibrary;
  dialog_.stage = FileDialog::Stage::kBrowse;
  dialog_.is_open_requested = true;
  const auto& paths = std::get<std::vector<std::string>>(fields_.value("particle.library"));
  dialog_.folder = !folder.empty() ? folder : start_folder(paths, settings_.folder);
  dialog_.picked.clear();
  dialog_.name.clear();
  dialog_.list();
}

void GuiApp::use_library(std::vector<std::string> paths) {
  settings_.folder = dialog_.folder;
  settings_.save(GuiSettings::folder_of(options_.settings_dir));
  fields_.value("particle.library") = std::move(paths);
  fields_.set_on("particle.library", true);
  dialog_.kind = FileDialog::Kind::kNone;
  ImGui::CloseCurrentPopup();
}

void GuiApp::draw_library_dialog() {
  const char* title = tr(Text::kDialogLibraryTitle);
  if (dialog_.is_open_requested) {
    ImGui::OpenPopup(title);
    dialog_.is_open_requested = false;
  }
  ImGui::SetNextWindowPos(ImGui::GetMainViewport()->GetCenter(), ImGuiCond_Appearing,
                          ImVec2(0.5f, 0.5f));
  ImGui::SetNextWindowSize(
      ImVec2(640.0f, std::min(ImGui::GetMainViewport()->Size.y - 20.0f, 460.0f)),
      ImGuiCond_Appearing);
  if (!ImGui::BeginPopupModal(title, nullptr, ImGuiWindowFlags_NoSavedSettings)) {
    dialog_.kind = FileDialog::Kind::kNone;
    return;
  }
  const int scripted = std::exchange(dialog_.scripted, 0);
  const bool is_no = scripted == 2 || (!ImGui::GetIO().WantTextInput &&
                                       ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape)));
  ImGui::TextWrapped("%s", tr(Text::kLibraryHelp));
  // The folder: up, typed, or entered from the list.
  if (ImGui::Button(tr(Text::kUp))) {
    dialog_.folder = fs::path(dialog_.folder).parent_path().string();
    dialog_.list();
  }
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", tr(Text::kUpTooltip));
  ImGui::SameLine();
  char buffer[1024];
  std::snprintf(buffer, sizeof(buffer), "%s", dialog_.folder.c_str());
  ImGui::SetNextItemWidth(-60.0f);
  if (ImGui::InputText(tr(Text::kFolder), buffer, sizeof(buffer),
                       ImGuiInputTextFlags_EnterReturnsTrue)) {
    dialog_.folder = buffer;
    dialog_.list();
  }
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", tr(Text::kFolderTooltip));
  const float footer = 3.0f * ImGui::GetFrameHeightWithSpacing();
  if (ImGui::BeginChild("##library_entries", ImVec2(0.0f, -footer), true)) {
    std::string enter;
    for (const std::string& sub : dialog_.folders) {
      if (ImGui::Selectable((sub + "/").c_str(), false)) enter = sub;
    }
    // A click picks a file or gives it back.
    for (const std::string& file : dialog_.files) {
      auto& picked = dialog_.picked;
      const auto found = std::find(picked.begin(), picked.end(), file);
      if (ImGui::Selectable(file.c_str(), found != picked.end())) {
        if (found != picked.end()) {
          picked.erase(found);
        } else {
          picked.push_back(file);
        }
      }
    }
    if (dialog_.folders.empty() && dialog_.files.empty()) {
      ImGui::TextDisabled("%s", trf(Text::kNoEntries, tr(Text::kMeshFiles)).c_str());
    }
    if (!enter.empty()) {
      dialog_.folder = (fs::path(dialog_.folder) / enter).string();
      dialog_.list();
    }
  }
  ImGui::EndChild();
  if (!dialog_.error.empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0.95f, 0.35f, 0.3f, 1.0f));
    ImGui::TextWrapped("%s", dialog_.error.c_str());
    ImGui::PopStyleColor();
  }
  // The picked files in list (name) order, as the loader orders a folder's.
  std::vector<std::string> picked_paths;
  for (const std::string& file : dialog_.files) {
    if (std::find(dialog_.picked.begin(), dialog_.picked.end(), file) != dialog_.picked.end()) {
      picked_paths.push_back((fs::path(dialog_.folder) / file).string());
    }
  }
  // Scripted: "yes" uses the picked files when there are any, else the folder.
  const bool is_yes = scripted == 1;
  if (picked_paths.empty()) {
    ImGui::BeginDisabled(dialog_.files.empty());
    if (wide_button(trf(Text::kUseFolder, dialog_.files.size()).c_str()) ||
        (is_yes && !dialog_.files.empty())) {
      use_library({dialog_.folder});
    }
    ImGui::EndDisabled();
    if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) {
      ImGui::SetTooltip("%s", tr(Text::kUseFolderTooltip));
    }
  } else if (wide_button(trf(Text::kUseFiles, picked_paths.size()).c_str()) || is_yes) {
    use_library(std::move(picked_paths));
  }
  if (dialog_.kind != FileDialog::Kind::kNone) {
    ImGui::SameLine();
    if (wide_button(tr(Text::kDialogCancel)) || is_no || (is_yes && dialog_.files.empty())) {
      dialog_.kind = FileDialog::Kind::kNone;
      ImGui::CloseCurrentPopup();
    }
  }
  ImGui::EndPopup();
}

}  // namespace aggpack::gui
