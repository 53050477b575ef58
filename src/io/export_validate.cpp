// Which format write() uses (resolve_format) and whether the options fit it (validate): the
// checks read the format's row (export_formats()), so a capability is declared once.

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "aggpack/core/error.h"
#include "aggpack/io/export.h"

namespace aggpack {

namespace fs = std::filesystem;

namespace {

// ".stl, .obj": the formats whose row `has` (a predicate on the row), in table order.
std::string formats_with(bool (*has)(const FormatInfo&)) {
  std::string text;
  for (const FormatInfo& info : export_formats()) {
    if (!has(info)) continue;
    if (!text.empty()) text += ", ";
    text += '.';
    text += info.name;
  }
  return text;
}

bool holds_packing(const FormatInfo& info) { return info.holds_packing; }
bool has_quadratic(const FormatInfo& info) { return info.has_quadratic; }
bool has_per_particle(const FormatInfo& info) { return info.has_per_particle; }
bool has_both_cells(const FormatInfo& info) { return info.has_surface && info.has_tetrahedra; }

const DeckInfo& deck_info(DeckKind kind) {
  for (const DeckInfo& deck : deck_kinds()) {
    if (deck.kind == kind) return deck;
  }
  throw InvalidInput("deck", "none", "a deck of the table");
}

void validate_deck(const ExportOptions& options, ExportFormat format) {
  const DeckOptions& deck = options.deck;
  if (deck.kind == DeckKind::kNone) return;
  const std::string name = deck_name(deck.kind);
  const ExportFormat deck_format = deck_info(deck.kind).format;
  if (format != deck_format) {
    throw InvalidInput("deck", name + " for ." + format_name(format),
                       "the ." + format_name(deck_format) + " format");
  }
  if (options.is_per_particle) {
    throw InvalidInput("per-particle", "true with --deck " + name, "one file for a deck");
  }
  if (options.abaqus_layout != AbaqusLayout::kElementSets) {
    throw InvalidInput("inp layout", "parts with --deck " + name, "sets");
  }
  if (options.is_quadratic && deck.kind == DeckKind::kAbaqus) {
    throw InvalidInput("quadratic", "true with --deck abaqus",
                       "C3D4 (Abaqus/Explicit has no C3D10; use --deck calculix)");
  }
  require_in_range("friction", deck.friction, 0.0, 10.0);
  require_positive("gravity", deck.gravity);
  require_positive("baffle speed", deck.baffle_speed);
  require_in_range("baffle position", deck.baffle_position, 0.0, 1e9);
  require_in_range("trough length", deck.trough_length, 0.0, 1e9);
  require_in_range("settle time", deck.settle_time, 0.0, 1e9);
  require_in_range("rest time", deck.rest_time, 0.0, 1e9);
  require_in_range("contact distance", deck.contact_distance, 0.0, 1e9);
  require_in_range("time step", deck.time_step, 0.0, 1e9);
}

// Options only a file holding the whole packing (native) takes, and the ones it cannot take.
void validate_packing_file(const ExportOptions& options, const FormatInfo& info) {
  const std::string format = "." + std::string(info.name);
  if (!info.holds_packing) {
    if (options.compression != 0) {
      throw InvalidInput("compression", std::to_string(options.compression) + " for " + format,
                         "only for " + formats_with(holds_packing));
    }
    if (options.write_xdmf) {
      throw InvalidInput("xdmf", "true for " + format, "only for " + formats_with(holds_packing));
    }
    return;
  }
  require_in_range("compression", options.compression, 0, 9);
  if (options.scale != 1.0) {
    throw InvalidInput("scale", format_value(options.scale) + " for " + format,
                       "1 (the native file stores metres)");
  }
}

}  // namespace

void validate(const ExportOptions& options, ExportFormat format) {
  const FormatInfo& info = format_info(format);
  const std::string name = "." + std::string(info.name);
  require_positive("scale", options.scale);
  validate(options.tetrahedra);
  const auto& material = options.material;
  require_positive("density", material.density);
  require_positive("youngs modulus", material.youngs_modulus);
  if (!(material.poisson_ratio > -1.0 && material.poisson_ratio < 0.5)) {
    throw InvalidInput("poisson ratio", format_value(material.poisson_ratio),
                       Wording{Sentence::kPoissonRange, {}});
  }
  const bool is_name_ok = !material.name.empty() && material.name.size() <= 32 &&
                          std::isalpha(static_cast<unsigned char>(material.name[0])) &&
                          std::all_of(material.name.begin(), material.name.end(),
                                      [](unsigned char c) { return std::isalnum(c) || c == '_'; });
  if (!is_name_ok) {
    throw InvalidInput("material name", "'" + material.name + "'",
                       Wording{Sentence::kMaterialName, {}});
  }
  if (options.is_quadratic && !info.has_quadratic) {
    throw InvalidInput("quadratic", "true for " + name,
                       "only for " + formats_with(has_quadratic) + " (C3D10)");
  }
  if (options.is_cut_to_box && format != ExportFormat::kStl) {
    throw InvalidInput("cut-to-box", "true for " + name, "only for .stl");
  }
  if (options.is_per_particle && !info.has_per_particle) {
    throw InvalidInput("per-particle", "true for " + name,
                       "only for " + formats_with(has_per_particle));
  }
  // A choice of cells only where both kinds are possible.
  if (options.cells != MeshCells::kDefault && !has_both_cells(info)) {
    throw InvalidInput("cells", "set for " + name, "only for " + formats_with(has_both_cells));
  }
  validate_packing_file(options, info);
  validate_deck(options, format);
}

ExportFormat resolve_format(const std::string& path, const ExportOptions& options) {
  if (options.format != ExportFormat::kAuto) return options.format;
  if (options.deck.kind != DeckKind::kNone) {
    // The deck picks the format; an extension naming another format is a mistake.
    const ExportFormat format = deck_info(options.deck.kind).format;
    ExportFormat named = ExportFormat::kAuto;
    try {
      named = format_from_extension(path);
    } catch (const InvalidInput&) {
    }
    if (named != ExportFormat::kAuto && named != format) {
      throw InvalidInput("output extension", "'" + fs::path(path).extension().string() + "'",
                         "." + format_name(format) + " for --deck " + deck_name(options.deck.kind));
    }
    return format;
  }
  fs::path file(path);
  while (!file.empty() && !file.has_filename()) file = file.parent_path();
  if (options.is_per_particle && file.extension().empty()) {
    // A folder without an extension: the first format that writes per-particle folders (STL).
    for (const FormatInfo& info : export_formats()) {
      if (info.has_per_particle) return info.format;
    }
  }
  return format_from_extension(path);
}

}  // namespace aggpack
