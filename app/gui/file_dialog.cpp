// aggpack-gui's Open and Export dialog: browse folders, pick or type a file name (the paper's
// default names), and answer the questions before an export (a result older than the panel's
// parameters, an existing file). The folder is remembered between runs (gui_settings.h).

#include "file_dialog.h"

#include <fmt/core.h>
#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <system_error>
#include <utility>

#include "aggpack/io/export.h"
#include "aggpack/io/mesh_read.h"
#include "gui_app.h"
#include "i18n.h"
#include "system_words.h"

namespace aggpack::gui {

namespace fs = std::filesystem;

void FileDialog::list() {
  std::error_code code;
  const fs::path dir = fs::absolute(folder.empty() ? fs::path(".") : fs::path(folder), code);
  std::vector<std::string> new_folders, new_files;
  fs::directory_iterator it(dir, fs::directory_options::skip_permission_denied, code);
  if (code) {
    error = trs(Text::kCannotReadFolder, dir.string(), system_reason_words(code));
    return;
  }
  for (; it != fs::directory_iterator(); it.increment(code)) {
    if (code) break;
    const std::string entry = it->path().filename().string();
    if (entry.empty() || entry[0] == '.') continue;
    std::error_code type_code;
    if (it->is_directory(type_code)) {
      new_folders.push_back(entry);
    } else if (is_listed(entry)) {
      new_files.push_back(entry);
    }
  }
  std::sort(new_folders.begin(), new_folders.end());
  std::sort(new_files.begin(), new_files.end());
  const std::string old_folder = folder;
  folder = dir.lexically_normal().string();
  if (folder.size() > 1 && folder.back() == '/') folder.pop_back();
  if (folder != old_folder) picked.clear();  // picks belong to the folder they were made in
  folders = std::move(new_folders);
  files = std::move(new_files);
  error.clear();
}

std::string FileDialog::path() const { return (fs::path(folder) / name).string(); }

std::string FileDialog::extension() const {
  if (kind == Kind::kLibrary) return "";
  return kind == Kind::kOpen ? std::string(".h5") : "." + format;
}

bool FileDialog::is_listed(const std::string& entry) const {
  if (kind != Kind::kLibrary) return fs::path(entry).extension().string() == extension();
  MeshFileFormat mesh_format{};
  return mesh_file_format(entry, mesh_format);
}

std::string default_export_name(const std::string& format, const std::string& stem) {
  if (format == "dat") return "rock.dat";
  return stem + "." + format;
}

void GuiApp::open_dialog(FileDialog::Kind kind, const std::string& format, DeckKind deck) {
  if (job_.is_running() || upload_.is_pending()) return;
  if (kind == FileDialog::Kind::kExport && !packing_) return;
  dialog_.kind = kind;
  dialog_.is_open_requested = true;
  // The folder of the last export (or of --export-name), else the remembered one.
  const std::string base_folder = fs::path(export_base_).parent_path().string();
  dialog_.folder =
      kind == FileDialog::Kind::kExport && !base_folder.empty() ? base_folder : settings_.folder;
  dialog_.format = format.empty() ? settings_.export_format : format;
  dialog_.deck = format.empty() ? DeckKind::kNone : deck;
  std::string stem = fs::path(export_base_).filename().string();
  if (stem.empty()) stem = "rock";
  dialog_.name = kind == FileDialog::Kind::kOpen   ? fs::path(open_path_).filename().string()
                 : dialog_.deck != DeckKind::kNone ? default_deck_name(dialog_.deck, stem)
                                                   : default_export_name(dialog_.format, stem);
  dialog_.list();
  dialog_.stage = kind == FileDialog::Kind::kExport && is_result_stale()
                      ? FileDialog::Stage::kAskStale
                      : FileDialog::Stage::kBrowse;
}

namespace {

// A button of the dialog's width share.
bool dialog_button(const char* label) {
  const float width =
      ImGui::CalcTextSize(label, nullptr, true).x + 2.0f * ImGui::GetStyle().FramePadding.x;
  return ImGui::Button(label, ImVec2(std::max(170.0f, width), 0.0f));
}

}  // namespace

void GuiApp::draw_file_dialog() {
  if (dialog_.kind == FileDialog::Kind::kNone) return;
  if (dialog_.kind == FileDialog::Kind::kLibrary) {
    draw_library_dialog();
    return;
  }
  const bool is_open = dialog_.kind == FileDialog::Kind::kOpen;
  const char* title = tr(is_open ? Text::kDialogOpenTitle : Text::kDialogExportTitle);
  if (dialog_.is_open_requested) {
    ImGui::OpenPopup(title);
    dialog_.is_open_requested = false;
  }
  const ImVec2 centre = ImGui::GetMainViewport()->GetCenter();
  ImGui::SetNextWindowPos(centre, ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
  // Taller with a solver deck's fields (and again when the format list picks or leaves a deck).
  auto dialog_size = [this] {
    const float tall = dialog_.deck != DeckKind::kNone ? 600.0f : 440.0f;
    return ImVec2(640.0f, std::min(ImGui::GetMainViewport()->Size.y - 20.0f, tall));
  };
  ImGui::SetNextWindowSize(dialog_size(), ImGuiCond_Appearing);
  if (!ImGui::BeginPopupModal(title, nullptr, ImGuiWindowFlags_NoSavedSettings)) {
    dialog_.kind = FileDialog::Kind::kNone;
    return;
  }
  const int scripted = std::exchange(dialog_.scripted, 0);
  const bool is_yes = scripted == 1;
  // Esc closes the dialog (as Cancel), unless a text field has the keyboard.
  const bool is_no = scripted == 2 || (!ImGui::GetIO().WantTextInput &&
                                       ImGui::IsKeyPressed(ImGui::GetKeyIndex(ImGuiKey_Escape)));
  auto close = [this] {
    dialog_.kind = FileDialog::Kind::kNone;
    ImGui::CloseCurrentPopup();
  };
  auto write_now = [this, &close] {
    settings_.folder = dialog_.folder;
    settings_.export_format = dialog_.format;
    settings_.save(GuiSettings::folder_of(options_.settings_dir));
    const std::string stem = plain_stem(fs::path(dialog_.name).stem().string());
    export_base_ = (fs::path(dialog_.folder) / stem).string();
    start_export(dialog_.format, dialog_.deck, dialog_.path());
    close();
  };
  if (dialog_.stage == FileDialog::Stage::kAskStale) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.75f, 0.3f, 1.0f));
    ImGui::TextWrapped("%s", tr(Text::kStaleTitle));
    ImGui::PopStyleColor();
    std::string keys;
    for (const std::string& key : changed_keys()) keys += (keys.empty() ? "" : ", ") + key;
    ImGui::TextWrapped("%s", trf(Text::kStaleText, keys).c_str());
    ImGui::Spacing();
    if (dialog_button(tr(Text::kExportShown)) || is_yes) {
      dialog_.stage = FileDialog::Stage::kBrowse;
    }
    ImGui::SameLine();
    if (dialog_button(tr(Text::kPackAgainFirst))) {
      close();
      start_pack();
    }
    ImGui::SameLine();
    if (dialog_button(tr(Text::kDialogCancel)) || is_no) close();
    ImGui::EndPopup();
    return;
  }
  if (dialog_.stage == FileDialog::Stage::kAskOverwrite) {
    ImGui::TextWrapped("%s", trf(Text::kAlreadyExists, dialog_.name, dialog_.folder).c_str());
    ImGui::TextWrapped("%s", tr(Text::kReplaceQuestion));
    ImGui::Spacing();
    if (dialog_button(tr(Text::kReplace)) || is_yes) write_now();
    ImGui::SameLine();
    if (dialog_button(tr(Text::kBack))) dialog_.stage = FileDialog::Stage::kBrowse;
    ImGui::SameLine();
    if (dialog_button(tr(Text::kDialogCancel)) || is_no) close();
    ImGui::EndPopup();
    return;
  }

  // Browsing: the format (export), the folder, its list, the name.
  if (!is_open) {
    // The formats of the table, then the complete solver decks (`aggpack export --deck`).
    const DeckKind old_deck = dialog_.deck;
    auto choose = [this](const std::string& format, DeckKind deck) {
      const std::string stem = plain_stem(fs::path(dialog_.name).stem().string());
      const std::string old_default = dialog_.deck != DeckKind::kNone
                                          ? default_deck_name(dialog_.deck, stem)
                                          : default_export_name(dialog_.format, stem);
      if (dialog_.name == old_default ||
          fs::path(dialog_.name).extension() == "." + dialog_.format) {
        dialog_.name = deck != DeckKind::kNone ? default_deck_name(deck, stem)
                                               : default_export_name(format, stem);
      }
      dialog_.format = format;
      dialog_.deck = deck;
      dialog_.list();
    };
    const std::string shown =
        dialog_.deck != DeckKind::kNone ? deck_title(dialog_.deck) : dialog_.format;
    ImGui::SetNextItemWidth(260.0f);
    if (ImGui::BeginCombo(tr(Text::kFormat), shown.c_str(), ImGuiComboFlags_HeightLargest)) {
      for (const FormatInfo& info : export_formats()) {
        const std::string name(info.name);
        const std::string format_title =
            name == "h5" ? std::string(tr(Text::kNativeFormat)) : std::string(info.title);
        if (ImGui::Selectable(fmt::format("{} ({})", format_title, name).c_str(),
                              name == dialog_.format && dialog_.deck == DeckKind::kNone)) {
          choose(name, DeckKind::kNone);
        }
      }
      ImGui::Separator();
      ImGui::TextDisabled("%s", tr(Text::kSolverModels));
      for (const DeckInfo& info : deck_kinds()) {
        if (ImGui::Selectable(deck_title(info.kind).c_str(), info.kind == dialog_.deck)) {
          choose(format_name(info.format), info.kind);
        }
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", deck_run_hint(info.kind));
      }
      ImGui::EndCombo();
    }
    if ((old_deck == DeckKind::kNone) != (dialog_.deck == DeckKind::kNone)) {
      const ImVec2 size = dialog_size();
      ImGui::SetWindowSize(size);
      ImGui::SetWindowPos(ImVec2(centre.x - 0.5f * size.x, centre.y - 0.5f * size.y));
    }
    if (ImGui::IsItemHovered()) {
      ImGui::SetTooltip("%s", tr(Text::kFormatTooltip));
    }
  }
  char buffer[1024];
  std::snprintf(buffer, sizeof(buffer), "%s", dialog_.folder.c_str());
  if (ImGui::Button(tr(Text::kUp))) {
    dialog_.folder = fs::path(dialog_.folder).parent_path().string();
    dialog_.list();
  }
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", tr(Text::kUpTooltip));
  ImGui::SameLine();
  ImGui::SetNextItemWidth(-60.0f);
  if (ImGui::InputText(tr(Text::kFolder), buffer, sizeof(buffer),
                       ImGuiInputTextFlags_EnterReturnsTrue)) {
    dialog_.folder = buffer;
    dialog_.list();
  }
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", tr(Text::kFolderTooltip));
  const bool has_deck = !is_open && dialog_.deck != DeckKind::kNone;
  const float footer = (has_deck ? 11.0f : 3.0f) * ImGui::GetFrameHeightWithSpacing();
  if (ImGui::BeginChild("##entries", ImVec2(0.0f, -footer), true)) {
    std::string enter;
    for (const std::string& sub : dialog_.folders) {
      if (ImGui::Selectable((sub + "/").c_str(), false, ImGuiSelectableFlags_AllowDoubleClick)) {
        enter = sub;
      }
    }
    for (const std::string& file : dialog_.files) {
      if (ImGui::Selectable(file.c_str(), file == dialog_.name,
                            ImGuiSelectableFlags_AllowDoubleClick)) {
        dialog_.name = file;
      }
    }
    if (dialog_.folders.empty() && dialog_.files.empty()) {
      ImGui::TextDisabled("%s", trf(Text::kNoEntries, dialog_.extension()).c_str());
    }
    if (!enter.empty()) {
      dialog_.folder = (fs::path(dialog_.folder) / enter).string();
      dialog_.list();
    }
  }
  ImGui::EndChild();
  std::snprintf(buffer, sizeof(buffer), "%s", dialog_.name.c_str());
  ImGui::SetNextItemWidth(-60.0f);
  if (ImGui::InputText(tr(Text::kName), buffer, sizeof(buffer))) dialog_.name = buffer;
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", tr(Text::kNameTooltip));
  if (!dialog_.error.empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(0.95f, 0.35f, 0.3f, 1.0f));
    ImGui::TextWrapped("%s", dialog_.error.c_str());
    ImGui::PopStyleColor();
  }
  // A deck's fields, checked as the library checks them: Export waits for valid values.
  const std::string deck_error = has_deck ? draw_deck_fields(dialog_.deck) : std::string();
  const bool has_name = !dialog_.name.empty() && deck_error.empty();
  ImGui::BeginDisabled(!has_name);
  if (dialog_button(tr(is_open ? Text::kDialogOpen : Text::kDialogExport)) ||
      (is_yes && has_name)) {
    std::error_code code;
    if (is_open) {
      settings_.folder = dialog_.folder;
      settings_.save(GuiSettings::folder_of(options_.settings_dir));
      open_path_ = dialog_.path();
      start_open(open_path_);
      close();
    } else if (fs::exists(dialog_.path(), code)) {
      dialog_.stage = FileDialog::Stage::kAskOverwrite;
    } else {
      write_now();
    }
  }
  ImGui::EndDisabled();
  if (is_yes && !has_name) {  // scripted: nothing to press; say why, as the dialog shows it
    set_status(deck_error.empty() ? std::string(tr(Text::kNoFileName)) : deck_error, true);
    close();
  }
  ImGui::SameLine();
  if (dialog_button(tr(Text::kDialogCancel)) || is_no) close();
  ImGui::EndPopup();
}

}  // namespace aggpack::gui
