// The Export dialog's solver decks (issue 18, item 5): the complete, runnable models of the
// paper's trough test that `aggpack export --deck` writes (Abaqus/Explicit, CalculiX, LS-DYNA,
// YADE), written by the library's write() with ExportOptions::deck. Here: their names in the
// dialog and menus, and the deck's fields (trough test and material) with their checks.

#include <fmt/core.h>
#include <imgui.h>

#include <string>
#include <vector>

#include "aggpack/core/error.h"
#include "aggpack/io/export.h"
#include "file_dialog.h"
#include "gui_app.h"

namespace aggpack::gui {

std::string default_deck_name(DeckKind deck, const std::string& stem) {
  for (const DeckInfo& info : deck_kinds()) {
    if (info.kind == deck) {
      return fmt::format("{}-{}.{}", plain_stem(stem), info.name, format_name(info.format));
    }
  }
  return default_export_name("inp", stem);
}

std::string plain_stem(const std::string& stem) {
  for (const DeckInfo& info : deck_kinds()) {
    const std::string ending = "-" + std::string(info.name);
    if (stem.size() > ending.size() &&
        stem.compare(stem.size() - ending.size(), ending.size(), ending) == 0) {
      return stem.substr(0, stem.size() - ending.size());
    }
  }
  return stem;
}

std::string deck_title(DeckKind deck) {
  const char* solver = "";
  switch (deck) {
    case DeckKind::kAbaqus:
      solver = "Abaqus/Explicit";
      break;
    case DeckKind::kCalculix:
      solver = "CalculiX";
      break;
    case DeckKind::kLsDyna:
      solver = "LS-DYNA";
      break;
    case DeckKind::kYade:
      solver = "YADE";
      break;
    case DeckKind::kNone:
      return "mesh only";
  }
  for (const DeckInfo& info : deck_kinds()) {
    if (info.kind == deck) return fmt::format("{} deck (.{})", solver, format_name(info.format));
  }
  return solver;
}

const char* deck_run_hint(DeckKind deck) {
  switch (deck) {
    case DeckKind::kAbaqus:
      return "rigid walls, a moving rigid baffle, general contact; run: abaqus job=NAME";
    case DeckKind::kCalculix:
      return "fixed floor and walls, a moving baffle, contact pairs between neighbours; run: "
             "ccx -i NAME";
    case DeckKind::kLsDyna:
      return "rigid walls, a rigid moving baffle, automatic contact; run: lsdyna i=NAME.k";
    case DeckKind::kYade:
      return "walls, a moving baffle wall, polyhedra engines; run: yade -n -x NAME.py";
    case DeckKind::kNone:
      break;
  }
  return "";
}

namespace {

const ImVec4 kErrorText(0.95f, 0.35f, 0.3f, 1.0f);
const ImVec4 kErrorFrame(0.55f, 0.15f, 0.12f, 1.0f);

// One field of the deck table: `field` is the name the library's check gives it.
struct DeckField {
  const char* label;
  const char* field;
  const char* tooltip;
  double* value;
};

// "invalid friction = 11 (allowed: [0, 10])" as "friction: 11 is not allowed; allowed: [0, 10]."
std::string plain_words(const InvalidInput& invalid) {
  const std::string message = invalid.what();
  const auto equals = message.find(" = ");
  const auto allowed = message.find(" (allowed: ");
  if (equals == std::string::npos || allowed == std::string::npos || allowed < equals ||
      message.back() != ')') {
    return plain_error(message);
  }
  const std::string value = message.substr(equals + 3, allowed - equals - 3);
  const std::string range = message.substr(allowed + 11, message.size() - allowed - 12);
  return fmt::format("{}: {} is not allowed; allowed: {}.", invalid.field(), value, range);
}

}  // namespace

std::string GuiApp::draw_deck_fields(DeckKind deck) {
  ExportOptions options;
  options.format = deck_kinds().front().format;
  for (const DeckInfo& info : deck_kinds()) {
    if (info.kind == deck) options.format = info.format;
  }
  options.deck = deck_options_;
  options.deck.kind = deck;
  options.material = deck_material_;
  std::string error, error_field;
  try {  // the library's own check: the words and ranges `aggpack export --deck` uses
    validate(options, options.format);
  } catch (const InvalidInput& invalid) {
    error = plain_words(invalid);
    error_field = invalid.field();
  } catch (const Error& other) {
    error = plain_error(other.what());
  }
  ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
  ImGui::TextWrapped("The paper's trough test: %s.", deck_run_hint(deck));
  ImGui::PopStyleColor();
  if (ImGui::IsItemHovered()) {
    ImGui::SetTooltip(
        "Settle under gravity (baffle still), then the baffle moves toward +x to the trough's "
        "end, then rest.\nThe deck's header lists what it assumes. SI units (m, s, kg, Pa).");
  }
  DeckOptions& d = deck_options_;
  std::vector<DeckField> fields = {
      {"friction mu", "friction",
       "Coulomb friction mu_s, particle-particle and particle-wall, "
       "[0, 10]",
       &d.friction},
      {"gravity m/s2", "gravity", "Gravity along -z (m/s^2), > 0", &d.gravity},
      {"baffle m/s", "baffle speed", "Speed of the baffle toward +x (m/s), > 0", &d.baffle_speed},
      {"baffle x m", "baffle position",
       "x of the baffle (m), at or beyond the particles' largest x; 0 = the container's end",
       &d.baffle_position},
      {"trough m", "trough length",
       "Trough length (m) from its start; 0 = twice the start-to-baffle length (the paper's "
       "baffle at the middle)",
       &d.trough_length},
      {"settle s", "settle time",
       "Step SETTLE (s), baffle still; 0 = twice the free fall of the highest particle",
       &d.settle_time},
      {"rest s", "rest time", "Step REST after the baffle (s), >= 0", &d.rest_time},
      {"density kg/m3", "density", "Density of the aggregate (kg/m^3), > 0",
       &deck_material_.density},
      {"E Pa", "youngs modulus", "Young's modulus of the aggregate (Pa), > 0",
       &deck_material_.youngs_modulus},
      {"Poisson nu", "poisson ratio", "Poisson's ratio of the aggregate, in (-1, 0.5)",
       &deck_material_.poisson_ratio},
  };
  if (deck == DeckKind::kCalculix) {
    fields.push_back({"contact m", "contact distance",
                      "Contact pairs between particles (and walls) closer than this (m); 0 = half "
                      "the largest particle radius",
                      &d.contact_distance});
  }
  if (deck == DeckKind::kYade) {
    fields.push_back({"time step s", "time step",
                      "Time step (s); 0 = from the particles' mass and contact stiffness",
                      &d.time_step});
  }
  if (ImGui::BeginTable("deck", 2, ImGuiTableFlags_SizingStretchSame)) {
    for (const DeckField& field : fields) {
      ImGui::TableNextColumn();
      const bool is_bad = error_field == field.field;
      if (is_bad) ImGui::PushStyleColor(ImGuiCol_FrameBg, kErrorFrame);
      ImGui::SetNextItemWidth(-110.0f);
      ImGui::InputDouble(field.label, field.value, 0.0, 0.0, "%.6g");
      if (is_bad) ImGui::PopStyleColor();
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", field.tooltip);
    }
    ImGui::EndTable();
  }
  if (!error.empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, kErrorText);
    ImGui::TextWrapped("%s", error.c_str());
    ImGui::PopStyleColor();
  }
  return error;
}

}  // namespace aggpack::gui
