#pragma once
// The state of aggpack-gui's Open and Export dialog (drawn by GuiApp, file_dialog.cpp): a folder
// with its subfolders and matching files listed for browsing, a file name field, and the
// questions asked before writing (a stale result, an existing file).

#include <string>
#include <vector>

#include "aggpack/io/export.h"

namespace aggpack::gui {

struct FileDialog {
  /// kLibrary: particle.library's folder or mesh files (library_dialog.cpp).
  enum class Kind { kNone, kOpen, kExport, kLibrary };
  /// What the dialog shows: browsing, or one of the questions before an export.
  enum class Stage { kBrowse, kAskStale, kAskOverwrite };

  Kind kind = Kind::kNone;
  Stage stage = Stage::kBrowse;
  bool is_open_requested = false;  ///< ImGui::OpenPopup on the next frame
  std::string format;              ///< export: export_formats() name ("stl", "dat", ...)
  /// export: a complete solver deck (`aggpack export --deck`) written in `format` (the deck's
  /// own, deck_kinds()), or kNone for the mesh alone.
  DeckKind deck = DeckKind::kNone;
  std::string folder;                ///< absolute folder shown
  std::string name;                  ///< file name in the folder
  std::string error;                 ///< why the last folder / file was refused ("" = none)
  std::vector<std::string> folders;  ///< subfolders of `folder` (names), sorted
  std::vector<std::string> files;    ///< files of `folder` with the dialog's extension, sorted
  std::vector<std::string> picked;   ///< kLibrary: the files picked in `folder`, in list order
  /// Scripted runs: the next frame answers the shown stage: 1 yes (the default button), 2 no
  /// (Cancel); 0 = none.
  int scripted = 0;

  /// Lists `folder` (sets `error` and keeps the old listing when it cannot be read).
  void list();
  /// The chosen file's full path.
  [[nodiscard]] std::string path() const;
  /// The extension the dialog lists and writes (".h5" for Open, "." + the format's for Export;
  /// rock.dat's ".dat"; "" for kLibrary, which lists mesh files: is_listed).
  [[nodiscard]] std::string extension() const;
  /// Whether the file `entry` is listed: its extension, or for kLibrary .stl, .obj or .ply in
  /// any case (as the library loader reads them).
  [[nodiscard]] bool is_listed(const std::string& entry) const;
};

/// The paper's default file name for an export format: "rock.dat" for rock.dat, else
/// `stem` + "." + the format's extension.
std::string default_export_name(const std::string& format, const std::string& stem);

/// The default file name of a solver deck: `stem` + "-" + deck_name() + its format's extension
/// ("rock-calculix.inp"), so it does not replace the mesh export of the same stem.
std::string default_deck_name(DeckKind deck, const std::string& stem);

/// `stem` without a deck's "-calculix" (...) ending: the stem the exports share.
std::string plain_stem(const std::string& stem);

/// What the dialog and the menus call a deck ("CalculiX deck (.inp)") and how it is run.
std::string deck_title(DeckKind deck);
const char* deck_run_hint(DeckKind deck);

}  // namespace aggpack::gui
