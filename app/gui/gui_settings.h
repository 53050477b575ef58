#pragma once
// aggpack-gui's settings kept between runs: a small key = value file, settings.ini, in
// $XDG_CONFIG_HOME/aggpack/ (or ~/.config/aggpack/), beside ImGui's own imgui.ini.

#include <string>

namespace aggpack::gui {

struct GuiSettings {
  std::string folder;                 ///< last folder of the Open / Export dialogs ("" = current)
  std::string export_format = "stl";  ///< last export format (export_formats() name)
  int color = 0;                      ///< ColorMode of the view
  bool show_fps = false;              ///< the frame-rate readout
  bool show_container = true;         ///< the container's outline
  std::string language;  ///< "en" or "zh_CN" as chosen in View > Language ("" = the locale's)

  /// The settings folder: `dir` if not empty, else $XDG_CONFIG_HOME/aggpack, else
  /// $HOME/.config/aggpack, else "" (no settings kept).
  static std::string folder_of(const std::string& dir);
  /// Reads `settings_dir`/settings.ini; missing file or unknown lines leave the defaults.
  static GuiSettings load(const std::string& settings_dir);
  /// Writes `settings_dir`/settings.ini (creating the folder); false when it cannot.
  bool save(const std::string& settings_dir) const;
};

}  // namespace aggpack::gui
