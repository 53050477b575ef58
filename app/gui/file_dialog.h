#pragma once
// The state of aggpack-gui's Open and Export dialog (drawn by GuiApp, file_dialog.cpp): a folder
// with its subfolders and matching files listed for browsing, a file name field, and the
// questions asked before writing (a stale result, an existing file).

#include <string>
#include <vector>

namespace aggpack::gui {

struct FileDialog {
  enum class Kind { kNone, kOpen, kExport };
  /// What the dialog shows: browsing, or one of the questions before an export.
  enum class Stage { kBrowse, kAskStale, kAskOverwrite };

  Kind kind = Kind::kNone;
  Stage stage = Stage::kBrowse;
  bool is_open_requested = false;    ///< ImGui::OpenPopup on the next frame
  std::string format;                ///< export: export_formats() name ("stl", "dat", ...)
  std::string folder;                ///< absolute folder shown
  std::string name;                  ///< file name in the folder
  std::string error;                 ///< why the last folder / file was refused ("" = none)
  std::vector<std::string> folders;  ///< subfolders of `folder` (names), sorted
  std::vector<std::string> files;    ///< files of `folder` with the dialog's extension, sorted
  /// Scripted runs: the next frame answers the shown stage: 1 yes (the default button), 2 no
  /// (Cancel); 0 = none.
  int scripted = 0;

  /// Lists `folder` (sets `error` and keeps the old listing when it cannot be read).
  void list();
  /// The chosen file's full path.
  [[nodiscard]] std::string path() const;
  /// The extension the dialog lists and writes (".h5" for Open, "." + the format's for Export;
  /// rock.dat's ".dat").
  [[nodiscard]] std::string extension() const;
};

/// The paper's default file name for an export format: "rock.dat" for rock.dat, else
/// `stem` + "." + the format's extension.
std::string default_export_name(const std::string& format, const std::string& stem);

}  // namespace aggpack::gui
