#include "gui_settings.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <system_error>

namespace aggpack::gui {

std::string GuiSettings::folder_of(const std::string& dir) {
  if (!dir.empty()) return dir;
  if (const char* xdg = std::getenv("XDG_CONFIG_HOME"); xdg != nullptr && *xdg != '\0') {
    return (std::filesystem::path(xdg) / "aggpack").string();
  }
  if (const char* home = std::getenv("HOME"); home != nullptr && *home != '\0') {
    return (std::filesystem::path(home) / ".config" / "aggpack").string();
  }
  return "";
}

GuiSettings GuiSettings::load(const std::string& settings_dir) {
  GuiSettings settings;
  if (settings_dir.empty()) return settings;
  std::ifstream in(std::filesystem::path(settings_dir) / "settings.ini");
  std::string line;
  while (std::getline(in, line)) {
    const auto equals = line.find('=');
    if (equals == std::string::npos) continue;
    const std::string key = line.substr(0, equals);
    const std::string value = line.substr(equals + 1);
    if (key == "folder") settings.folder = value;
    if (key == "export_format" && !value.empty()) settings.export_format = value;
    if (key == "color") settings.color = std::atoi(value.c_str()) % 3;
    if (key == "show_fps") settings.show_fps = value == "1";
    if (key == "show_container") settings.show_container = value != "0";
    if (key == "language") settings.language = value;
  }
  if (settings.color < 0) settings.color = 0;
  return settings;
}

bool GuiSettings::save(const std::string& settings_dir) const {
  if (settings_dir.empty()) return false;
  std::error_code error;
  std::filesystem::create_directories(settings_dir, error);
  std::ofstream out(std::filesystem::path(settings_dir) / "settings.ini");
  if (!out) return false;
  out << "folder=" << folder << "\n"
      << "export_format=" << export_format << "\n"
      << "color=" << color << "\n"
      << "show_fps=" << (show_fps ? 1 : 0) << "\n"
      << "show_container=" << (show_container ? 1 : 0) << "\n"
      << "language=" << language << "\n";
  return static_cast<bool>(out);
}

}  // namespace aggpack::gui
