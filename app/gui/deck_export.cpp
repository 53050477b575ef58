// The Export dialog's solver decks (issue 18, item 5): the complete, runnable models of the
// paper's trough test that `aggpack export --deck` writes (Abaqus/Explicit, CalculiX, LS-DYNA,
// YADE), written by the library's write() with ExportOptions::deck. Here: their names in the
// dialog and menus, and the deck's fields (trough test and material) with their checks.

#include <fmt/core.h>
#include <imgui.h>

#include <string>
#include <string_view>
#include <vector>

#include "aggpack/core/error.h"
#include "aggpack/io/export.h"
#include "error_colours.h"
#include "file_dialog.h"
#include "gui_app.h"
#include "i18n.h"
#include "library_words.h"

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
  for (const DeckInfo& info : deck_kinds()) {
    if (info.kind == deck) return trs(Text::kDeckTitle, info.title, format_name(info.format));
  }
  return tr(Text::kMeshOnly);
}

namespace {

// The GUI's words for what each deck models and how to run it (translated in i18n/); a deck
// without a line here shows no hint.
struct DeckHint {
  DeckKind kind;
  Text hint;
};
constexpr DeckHint kDeckHints[] = {{DeckKind::kAbaqus, Text::kHintAbaqus},
                                   {DeckKind::kCalculix, Text::kHintCalculix},
                                   {DeckKind::kLsDyna, Text::kHintLsDyna},
                                   {DeckKind::kYade, Text::kHintYade}};

}  // namespace

const char* deck_run_hint(DeckKind deck) {
  for (const DeckHint& entry : kDeckHints) {
    if (entry.kind == deck) return tr(entry.hint);
  }
  return "";
}

namespace {

// One field of the deck table: `field` is the name the library's check gives it.
struct DeckField {
  Text label;
  const char* field;
  Text tooltip;
  double* value;
};

}  // namespace

std::string GuiApp::draw_deck_fields(DeckKind deck) {
  const DeckInfo* row = nullptr;  // the deck's row; none for DeckKind::kNone
  for (const DeckInfo& info : deck_kinds()) {
    if (info.kind == deck) row = &info;
  }
  ExportOptions options;
  options.format = (row != nullptr ? *row : deck_kinds().front()).format;
  options.deck = deck_options_;
  options.deck.kind = deck;
  options.material = deck_material_;
  std::string error, error_field;
  try {  // the library's own check: the words and ranges `aggpack export --deck` uses
    validate(options, options.format);
  } catch (const InvalidInput& invalid) {
    error = error_words(invalid);
    error_field = invalid.field();
  } catch (const Error& other) {
    error = error_words(other);
  }
  ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
  ImGui::TextWrapped("%s", trf(Text::kTroughTest, deck_run_hint(deck)).c_str());
  ImGui::PopStyleColor();
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", tr(Text::kTroughTooltip));
  DeckOptions& d = deck_options_;
  std::vector<DeckField> fields = {
      {Text::kDeckFriction, "friction", Text::kDeckFrictionTooltip, &d.friction},
      {Text::kDeckGravity, "gravity", Text::kDeckGravityTooltip, &d.gravity},
      {Text::kDeckBaffleSpeed, "baffle speed", Text::kDeckBaffleSpeedTooltip, &d.baffle_speed},
      {Text::kDeckBafflePosition, "baffle position", Text::kDeckBafflePositionTooltip,
       &d.baffle_position},
      {Text::kDeckTroughLength, "trough length", Text::kDeckTroughLengthTooltip, &d.trough_length},
      {Text::kDeckSettle, "settle time", Text::kDeckSettleTooltip, &d.settle_time},
      {Text::kDeckRest, "rest time", Text::kDeckRestTooltip, &d.rest_time},
      {Text::kDeckDensity, "density", Text::kDeckDensityTooltip, &deck_material_.density},
      {Text::kDeckYoungs, "youngs modulus", Text::kDeckYoungsTooltip,
       &deck_material_.youngs_modulus},
      {Text::kDeckPoisson, "poisson ratio", Text::kDeckPoissonTooltip,
       &deck_material_.poisson_ratio},
  };
  // The options of one deck only: shown for the decks whose row lists them.
  const DeckField own_fields[] = {
      {Text::kDeckContact, "contact distance", Text::kDeckContactTooltip, &d.contact_distance},
      {Text::kDeckTimeStep, "time step", Text::kDeckTimeStepTooltip, &d.time_step}};
  const std::vector<std::string_view> no_options;
  for (const std::string_view name : row != nullptr ? row->own_options : no_options) {
    for (const DeckField& field : own_fields) {
      if (name == field.field) fields.push_back(field);
    }
  }
  if (ImGui::BeginTable("##deck", 2, ImGuiTableFlags_SizingStretchSame)) {
    for (const DeckField& field : fields) {
      ImGui::TableNextColumn();
      const bool is_bad = error_field == field.field;
      if (is_bad) ImGui::PushStyleColor(ImGuiCol_FrameBg, kErrorFrame);
      ImGui::SetNextItemWidth(-110.0f);
      ImGui::InputDouble(tr(field.label), field.value, 0.0, 0.0, "%.6g");
      if (is_bad) ImGui::PopStyleColor();
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", tr(field.tooltip));
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
