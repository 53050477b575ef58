#pragma once
// Words of the GUI's texts for its language tests (library_words_test, library_errors_test): the
// English words of a text, whether it has Chinese, and the names kept as they are in every
// language.

#include <regex>
#include <set>
#include <string>

namespace aggpack::gui::test_words {

/// Words of three or more characters ("allowed", "format_name", "HDF5").
inline std::set<std::string> english_words_of(const std::string& text) {
  static const std::regex word("[A-Za-z_][A-Za-z0-9_]{2,}");
  std::set<std::string> words;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), word); it != std::sregex_iterator();
       ++it) {
    words.insert(it->str());
  }
  return words;
}

/// Whether the UTF-8 text has a character of three bytes (the CJK block).
inline bool has_chinese_text(const std::string& text) {
  for (const char c : text) {
    if ((static_cast<unsigned char>(c) & 0xF0U) == 0xE0U) return true;
  }
  return false;
}

/// Names that stay as they are in every language: the program and other programs (TetGen, Qhull),
/// formats and file extensions, HDF5 attributes, a configuration value as typed ("true"), the
/// keywords of a mesh file ("facet normal", "outer loop") and of a PLY header ("element",
/// "property list"), the NUL character.
inline bool is_kept_name(const std::string& word) {
  static const std::set<std::string> names = {"HDF5",   "aggpack",  "format_name", "format_version",
                                              "true",   "TetGen",   "ITZ",         "PNG",
                                              "FIFO",   "cgroup",   "ulimit",      "STL",
                                              "ASCII",  "OpenGL",   "OBJ",         "facet",
                                              "normal", "outer",    "loop",        "vertex",
                                              "solid",  "endsolid", "stl",         "obj",
                                              "ply",    "Qhull",    "NUL",         "CPU"};
  static const std::set<std::string> ply_header = {
      "PLY", "format", "element", "property", "list", "face", "end_header", "vertex_indices"};
  return names.count(word) > 0 || ply_header.count(word) > 0;
}

}  // namespace aggpack::gui::test_words
