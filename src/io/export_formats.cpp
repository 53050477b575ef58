// The format table and the deck table: the one place that lists aggpack's output formats (names,
// extensions, what each file can hold, writer) and solver decks. Everything else (write(),
// validate(), the config's [output] keys, the CLI help, the GUI) reads these rows.

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "aggpack/core/error.h"
#include "aggpack/io/mesomodel_files.h"
#include "aggpack/io/native.h"
#include "deck_common.h"
#include "export_detail.h"

namespace aggpack {

namespace {

std::string lower(std::string_view text) {
  std::string out(text);
  std::transform(out.begin(), out.end(), out.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return out;
}

// The native row's writer: the native file's own writer, same bytes as write_packing.
void write_native(const Packing& packing, const std::string& path, const ExportOptions& options,
                  ExportSummary& summary) {
  write_packing(packing, path,
                {.overwrite = options.overwrite,
                 .compression = options.compression,
                 .write_xdmf = options.write_xdmf});
  summary.files += options.write_xdmf ? 2 : 1;
}

bool is_named(std::string_view name, const std::vector<std::string_view>& aliases,
              const std::string& key) {
  return key == name || std::find(aliases.begin(), aliases.end(), key) != aliases.end();
}

// Appends ", name (alias, alias)" (no comma at the start of `text`), for messages.
void append_names(std::string& text, std::string_view name,
                  const std::vector<std::string_view>& aliases) {
  if (!text.empty()) text += ", ";
  text += name;
  for (std::size_t i = 0; i < aliases.size(); ++i) {
    text += i == 0 ? " (" : ", ";
    text += aliases[i];
  }
  if (!aliases.empty()) text += ')';
}

// "h5 (native), stl, ...": every row's name and aliases.
std::string format_names_text() {
  std::string text;
  for (const FormatInfo& info : export_formats()) append_names(text, info.name, info.aliases);
  return text;
}

}  // namespace

const std::vector<FormatInfo>& export_formats() {
  using enum ExportFormat;
  static const std::vector<FormatInfo> formats = {
      {.format = kNative,
       .name = "h5",
       .output_key = "native",
       .aliases = {"native"},
       .title = "native .h5",
       .holds_packing = true,
       .write_file = write_native},
      {.format = kStl,
       .name = "stl",
       .output_key = "stl",
       .aliases = {},
       .title = "STL",
       .has_surface = true,
       .default_cells = MeshCells::kSurface,
       .has_per_particle = true,
       .has_ascii = true,
       .write_mesh = detail::write_stl},
      {.format = kObj,
       .name = "obj",
       .output_key = "obj",
       .aliases = {},
       .title = "OBJ",
       .has_surface = true,
       .default_cells = MeshCells::kSurface,
       .has_per_particle = true,
       .write_mesh = detail::write_obj},
      {.format = kVtu,
       .name = "vtu",
       .output_key = "vtu",
       .aliases = {"vtk"},
       .title = "VTK .vtu",
       .has_surface = true,
       .has_tetrahedra = true,
       .default_cells = MeshCells::kSurface,
       .write_mesh = detail::write_vtu,
       .write_mesomodel = write_mesomodel_vtu},
      {.format = kRockDat,
       .name = "dat",
       .output_key = "dat",
       .aliases = {"rock.dat", "rockdat"},
       .title = "rock.dat",
       .has_tetrahedra = true,
       .default_cells = MeshCells::kTetrahedra,
       .write_mesh = detail::write_rock_dat},
      {.format = kAbaqus,
       .name = "inp",
       .output_key = "inp",
       .aliases = {"abaqus", "calculix"},
       .title = "Abaqus .inp",
       .has_tetrahedra = true,
       .has_quadratic = true,
       .default_cells = MeshCells::kTetrahedra,
       .write_mesh = detail::write_abaqus,
       .write_mesomodel = write_mesomodel_inp},
      {.format = kGmsh,
       .name = "msh",
       .output_key = "msh",
       .aliases = {"gmsh"},
       .title = "Gmsh .msh",
       .has_surface = true,
       .has_tetrahedra = true,
       .default_cells = MeshCells::kTetrahedra,
       .write_mesh = detail::write_gmsh,
       .write_mesomodel = write_mesomodel_msh},
      {.format = kLsDyna,
       .name = "k",
       .output_key = "k",
       .aliases = {"key", "lsdyna", "ls-dyna"},
       .title = "LS-DYNA .k",
       .has_tetrahedra = true,
       .default_cells = MeshCells::kTetrahedra,
       .write_mesh = detail::write_lsdyna},
      {.format = kAnsysApdl,
       .name = "mac",
       .output_key = "apdl",
       .aliases = {"apdl", "ansys"},
       .title = "ANSYS APDL .mac",
       .has_tetrahedra = true,
       .default_cells = MeshCells::kTetrahedra,
       .write_mesh = detail::write_ansys},
      {.format = kYade,
       .name = "py",
       .output_key = "yade",
       .aliases = {"yade"},
       .title = "YADE .py",
       .has_surface = true,
       .default_cells = MeshCells::kSurface,
       .write_mesh = detail::write_yade},
  };
  return formats;
}

const std::vector<DeckInfo>& deck_kinds() {
  static const std::vector<DeckInfo> decks = {
      {.kind = DeckKind::kAbaqus,
       .name = "abaqus",
       .title = "Abaqus/Explicit",
       .aliases = {},
       .format = ExportFormat::kAbaqus,
       .write_mesh = detail::write_deck_abaqus},
      {.kind = DeckKind::kCalculix,
       .name = "calculix",
       .title = "CalculiX",
       .aliases = {"ccx"},
       .format = ExportFormat::kAbaqus,
       .own_options = {"contact distance"},
       .write_mesh = detail::write_deck_calculix},
      {.kind = DeckKind::kLsDyna,
       .name = "lsdyna",
       .title = "LS-DYNA",
       .aliases = {"ls-dyna"},
       .format = ExportFormat::kLsDyna,
       .write_mesh = detail::write_deck_lsdyna},
      {.kind = DeckKind::kYade,
       .name = "yade",
       .title = "YADE",
       .aliases = {},
       .format = ExportFormat::kYade,
       .own_options = {"time step"},
       .write_mesh = detail::write_deck_yade},
  };
  return decks;
}

const FormatInfo& format_info(ExportFormat format) {
  for (const FormatInfo& info : export_formats()) {
    if (info.format == format) return info;
  }
  throw InvalidInput("format", "auto", "a format of the table (" + format_names_text() + ")");
}

const std::vector<std::string>& output_format_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> list;
    for (const FormatInfo& info : export_formats()) list.emplace_back(info.output_key);
    return list;
  }();
  return names;
}

std::string format_name(ExportFormat format) {
  if (format == ExportFormat::kAuto) return "auto";
  return std::string(format_info(format).name);
}

ExportFormat parse_export_format(const std::string& name) {
  const std::string key = lower(name);
  for (const FormatInfo& info : export_formats()) {
    if (is_named(info.name, info.aliases, key)) return info.format;
  }
  throw InvalidInput("format", "'" + name + "'", format_names_text());
}

ExportFormat format_from_extension(const std::string& path) {
  std::filesystem::path file(path);
  while (!file.empty() && !file.has_filename()) file = file.parent_path();
  const std::string extension = file.extension().string();
  const std::string allowed = "one of " + format_names_text() + ", or give --format";
  if (extension.size() < 2) {
    throw InvalidInput("output extension", "'" + file.string() + "'", allowed);
  }
  try {
    return parse_export_format(extension.substr(1));
  } catch (const InvalidInput&) {
    throw InvalidInput("output extension", "'" + extension + "'", allowed);
  }
}

DeckKind parse_deck_kind(const std::string& name) {
  const std::string key = lower(name);
  if (key == "none") return DeckKind::kNone;
  std::string allowed = "none";
  for (const DeckInfo& deck : deck_kinds()) {
    if (is_named(deck.name, deck.aliases, key)) return deck.kind;
    append_names(allowed, deck.name, deck.aliases);
  }
  throw InvalidInput("deck", "'" + name + "'", allowed);
}

std::string deck_name(DeckKind kind) {
  for (const DeckInfo& deck : deck_kinds()) {
    if (deck.kind == kind) return std::string(deck.name);
  }
  return "none";
}

}  // namespace aggpack
