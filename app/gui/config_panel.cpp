// The configuration sections of the panel, drawn from the schema: one widget per key that applies
// to the current choices, labelled with the key, its tooltip the key's doc line, allowed range
// and default (aggpack/config/schema.h). Only the sieve table has a widget of its own. In
// Chinese the labels, doc lines and word values come from i18n/keys_zh_CN.h (the key's name
// stays in the tooltip: it is what a TOML file or `--set` takes).

#include <fmt/core.h>
#include <imgui.h>

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <map>

#include "aggpack/core/error.h"
#include "aggpack/pack/grading.h"
#include "error_colours.h"
#include "gui_app.h"
#include "i18n.h"
#include "library_words.h"

namespace aggpack::gui {

namespace {

// A step for the +/- buttons: a tenth of the value's order of magnitude.
double step_for(double value) {
  if (value == 0.0 || !std::isfinite(value)) return 0.001;
  return std::pow(10.0, std::floor(std::log10(std::abs(value))) - 1.0);
}

// A key's doc line in the current language (the schema's own in English).
const char* key_doc(const Key<PackConfig>& key) {
  const char* chinese = language() == Language::kChinese ? key_doc_chinese(key.name) : nullptr;
  return chinese != nullptr ? chinese : key.doc.c_str();
}

// A word value as the list shows it: in Chinese its words and the word ("长方体 (box)"). Made
// once per language and word, so drawing a list allocates nothing (the window's thread only).
const std::string& shown_word(const std::string& word) {
  static std::array<std::map<std::string, std::string, std::less<>>, 2> cache;
  const bool is_chinese = language() == Language::kChinese;
  auto& shown = cache[is_chinese ? 1 : 0];
  auto found = shown.find(word);
  if (found == shown.end()) {
    const char* chinese = is_chinese ? word_chinese(word) : nullptr;
    found = shown.emplace(word, chinese != nullptr ? fmt::format("{} ({})", chinese, word) : word)
                .first;
  }
  return found->second;
}

void key_tooltip(const Key<PackConfig>& key, const KeyView& view) {
  if (!ImGui::IsItemHovered()) return;
  // Said of input alpha beside its doc line: why the measured alpha of the result differs.
  const std::string unit = key.unit.empty() || key.unit == "-" ? "" : " " + key.unit;
  ImGui::SetTooltip("%s",
                    trf(Text::kKeyTooltip, key_doc(key), key.name, allowed_words(view), unit,
                        default_words(view, *key.default_value, key.default_from, key.default_text),
                        key.name == "particle.alpha" ? tr(Text::kAlphaNote) : "")
                        .c_str());
}

// Typed values beyond a closed end of the range are clamped to it (an open end cannot be
// reached: such a value stays and its field says why).
template <typename Number>
void clamp_to_range(Number& number, const Range& range) {
  if (range.lo_end == End::kClosed && static_cast<double>(number) < range.lo) {
    number = static_cast<Number>(range.lo);
  }
  if (range.hi_end == End::kClosed && static_cast<double>(number) > range.hi) {
    number = static_cast<Number>(range.hi);
  }
}

}  // namespace

void GuiApp::draw_config_section(const char* title, const std::vector<std::string>& tables) {
  if (!ImGui::CollapsingHeader(title, ImGuiTreeNodeFlags_DefaultOpen)) return;
  const auto& schema = pack_schema();
  const auto views = key_views(schema);
  const PackConfig draft = fields_.draft();
  // A key another key excludes while that one is given (target_fraction beside target_count).
  const auto is_excluded = [&](const std::string& name) {
    for (const auto& other : schema.keys) {
      if (other.excludes == name && fields_.is_on(other.name)) return true;
    }
    return false;
  };
  for (const auto& table : tables) {
    for (std::size_t i = 0; i < schema.keys.size(); ++i) {
      const auto& key = schema.keys[i];
      if (key.name.rfind(table + ".", 0) != 0 || !ConfigFields::is_editable(key) ||
          !key.scope(draft) || is_excluded(key.name)) {
        continue;
      }
      draw_key(key, views[i]);
    }
  }
}

void GuiApp::draw_key(const Key<PackConfig>& key, const KeyView& view) {
  // The key without its table ("radius"), or the whole key where another table has a key of that
  // name ("container.kind", "grading.kind").
  // In Chinese: the catalogue's label. Made once per language (key_labels_), not per frame.
  const auto& keys = pack_schema().keys;
  if (key_labels_.empty()) {
    for (const auto& each : keys) {
      const std::string short_name = each.name.substr(each.name.find('.') + 1);
      const bool is_ambiguous = std::count_if(keys.begin(), keys.end(), [&](const auto& other) {
                                  return other.name.substr(other.name.find('.') + 1) == short_name;
                                }) > 1;
      const char* chinese =
          language() == Language::kChinese ? key_label_chinese(each.name) : nullptr;
      const std::string shown = chinese != nullptr ? std::string(chinese)
                                : is_ambiguous     ? each.name
                                                   : short_name;
      key_labels_.push_back(shown + "##" + each.name);
    }
  }
  const std::string& label = key_labels_[static_cast<std::size_t>(&key - keys.data())];
  Value& value = fields_.value(key.name);
  // The field's error in plain words, right under it.
  struct ErrorLine {
    const std::map<std::string, std::string>& errors;
    const std::string& name;
    ~ErrorLine() {
      const auto found = errors.find(name);
      if (found == errors.end()) return;
      ImGui::PushStyleColor(ImGuiCol_Text, kErrorText);
      ImGui::PushTextWrapPos(0.0f);
      ImGui::TextUnformatted(found->second.c_str());
      ImGui::PopTextWrapPos();
      ImGui::PopStyleColor();
    }
  } error_line{field_errors_, key.name};
  if (key.presence == Presence::kOptional && key.type != ValueType::kSieve) {
    bool is_on = fields_.is_on(key.name);
    if (ImGui::Checkbox(("##on" + key.name).c_str(), &is_on)) fields_.set_on(key.name, is_on);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", trf(Text::kGiveKey, key.name).c_str());
    ImGui::SameLine();
    // A list of paths is chosen with its dialog, which switches it on.
    const bool is_disabled = !is_on && key.type != ValueType::kPathList;
    if (is_disabled) ImGui::BeginDisabled();
    draw_key_input(key, view, label, value);
    if (is_disabled) ImGui::EndDisabled();
    return;
  }
  draw_key_input(key, view, label, value);
}

void GuiApp::draw_key_input(const Key<PackConfig>& key, const KeyView& view,
                            const std::string& label, Value& value) {
  switch (key.type) {
    case ValueType::kWord: {
      auto& word = std::get<std::string>(value);
      if (ImGui::BeginCombo(label.c_str(), shown_word(word).c_str())) {
        for (const auto& choice : key.words) {
          ImGui::PushID(choice.c_str());
          if (ImGui::Selectable(shown_word(choice).c_str(), choice == word)) word = choice;
          ImGui::PopID();
        }
        ImGui::EndCombo();
      }
      break;
    }
    case ValueType::kFloat: {
      auto& number = std::get<double>(value);
      const bool is_bad = !key.range.contains(number) || field_errors_.count(key.name) > 0;
      if (is_bad) ImGui::PushStyleColor(ImGuiCol_FrameBg, kErrorFrame);
      const double step = step_for(number);
      const std::string format =
          key.unit.empty() || key.unit == "-" ? std::string("%.4g") : "%.4g " + key.unit;
      if (ImGui::InputDouble(label.c_str(), &number, step, 10.0 * step, format.c_str())) {
        clamp_to_range(number, key.range);
      }
      if (is_bad) ImGui::PopStyleColor();
      break;
    }
    case ValueType::kInteger: {
      auto& number = std::get<std::int64_t>(value);
      const bool is_bad =
          !key.range.contains(static_cast<double>(number)) || field_errors_.count(key.name) > 0;
      if (is_bad) ImGui::PushStyleColor(ImGuiCol_FrameBg, kErrorFrame);
      const std::int64_t step = 1, fast = 100;
      if (ImGui::InputScalar(label.c_str(), ImGuiDataType_S64, &number, &step, &fast)) {
        clamp_to_range(number, key.range);
      }
      if (is_bad) ImGui::PopStyleColor();
      break;
    }
    case ValueType::kBool:
      ImGui::Checkbox(label.c_str(), &std::get<bool>(value));
      break;
    case ValueType::kSieve:
      key_tooltip(key, view);
      draw_sieve_table(std::get<std::vector<SieveRow>>(value));
      return;
    case ValueType::kPathList: {
      // particle.library: what is chosen (a folder or file, or how many), and the dialog.
      const auto& paths = std::get<std::vector<std::string>>(value);
      const std::string shown = paths.empty()       ? std::string(tr(Text::kNoLibrary))
                                : paths.size() == 1 ? paths.front()
                                                    : trs(Text::kLibraryFiles, paths.size());
      if (ImGui::Button(tr(Text::kBrowse))) open_library_dialog();
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", tr(Text::kBrowseTooltip));
      ImGui::SameLine();
      ImGui::TextUnformatted(shown.c_str());
      if (paths.size() > 1 && ImGui::IsItemHovered()) {
        std::string list;
        for (const std::string& path : paths) list += path + "\n";
        ImGui::SetTooltip("%s", list.c_str());
      }
      ImGui::SameLine();
      ImGui::TextUnformatted(label.substr(0, label.find("##")).c_str());
      break;
    }
    case ValueType::kNumberList:
    case ValueType::kPath:
      return;  // no pack key of these kinds is edited in the panel
  }
  key_tooltip(key, view);
}

void GuiApp::draw_sieve_table(std::vector<SieveRow>& rows) {
  // The library's own check, so the panel states the rule in the words Pack would use; the
  // field it names ("grading.sieve[2].size") marks the cell.
  std::string error, error_field;
  try {
    validate(Grading{.kind = GradingKind::kSieve, .sieve = rows});
  } catch (const InvalidInput& invalid) {
    error = error_words(invalid);
    error_field = invalid.field();
  } catch (const Error& other) {
    error = error_words(other);
  }
  ImGui::TextUnformatted(tr(Text::kSieveTitle));
  int insert_after = -1, remove = -1;
  const float button_width = ImGui::GetFrameHeight();
  constexpr ImGuiTableFlags kTableFlags =
      ImGuiTableFlags_BordersInnerV | ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingStretchProp;
  if (ImGui::BeginTable("##sieve", 4, kTableFlags)) {
    ImGui::TableSetupColumn("#", ImGuiTableColumnFlags_WidthFixed);
    ImGui::TableSetupColumn(tr(Text::kSieveSize), ImGuiTableColumnFlags_WidthStretch, 1.0f);
    ImGui::TableSetupColumn(tr(Text::kSievePassing), ImGuiTableColumnFlags_WidthStretch, 1.0f);
    ImGui::TableSetupColumn("##rows", ImGuiTableColumnFlags_WidthFixed,
                            2.0f * button_width + ImGui::GetStyle().ItemSpacing.x);
    ImGui::TableHeadersRow();
    for (int k = 0; k < static_cast<int>(rows.size()); ++k) {
      SieveRow& row = rows[static_cast<std::size_t>(k)];
      const std::string field = fmt::format("grading.sieve[{}]", k);
      ImGui::PushID(k);
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::AlignTextToFramePadding();
      ImGui::Text("%d", k);
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", trf(Text::kSieveRow, k, k).c_str());
      auto cell = [&error_field, &error](const std::string& name, const char* id, double* value,
                                         const char* format, const char* tooltip) {
        ImGui::TableNextColumn();
        const bool is_bad = error_field == name;
        if (is_bad) ImGui::PushStyleColor(ImGuiCol_FrameBg, kErrorFrame);
        ImGui::SetNextItemWidth(-FLT_MIN);
        ImGui::InputDouble(id, value, 0.0, 0.0, format);
        if (is_bad) ImGui::PopStyleColor();
        if (ImGui::IsItemHovered()) {
          ImGui::SetTooltip("%s\n%s%s%s", tooltip, name.c_str(), is_bad ? "\n\n" : "",
                            is_bad ? error.c_str() : "");
        }
      };
      cell(field + ".size", "##size", &row.size, tr(Text::kSieveCellFormat),
           tr(Text::kSieveSizeTooltip));
      cell(field + ".percent_passing", "##percent", &row.percent_passing, "%.4g",
           tr(Text::kSievePassingTooltip));
      ImGui::TableNextColumn();
      if (ImGui::Button("+", ImVec2(button_width, 0))) insert_after = k;
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", tr(Text::kSieveInsert));
      ImGui::SameLine();
      ImGui::BeginDisabled(rows.size() <= 2);  // a table needs two sieves
      if (ImGui::Button("-", ImVec2(button_width, 0))) remove = k;
      ImGui::EndDisabled();
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", tr(Text::kSieveRemove));
      ImGui::PopID();
    }
    ImGui::EndTable();
  }
  if (insert_after >= 0) {
    const auto after = static_cast<std::size_t>(insert_after);
    const SieveRow& row = rows[after];
    // Midway in d with the percent interpolated (P is linear in d between sieves), or a larger
    // sieve passing 100 % after the last: either way the grading is unchanged until edited.
    const SieveRow added =
        after + 1 < rows.size()
            ? SieveRow{.size = 0.5 * (row.size + rows[after + 1].size),
                       .percent_passing =
                           0.5 * (row.percent_passing + rows[after + 1].percent_passing)}
            : SieveRow{.size = 1.25 * row.size, .percent_passing = 100.0};
    rows.insert(rows.begin() + insert_after + 1, added);
  } else if (remove >= 0) {
    rows.erase(rows.begin() + remove);
  }
  ImGui::PushTextWrapPos(0.0f);
  if (!error.empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, kErrorText);
    ImGui::TextUnformatted(error.c_str());
    ImGui::PopStyleColor();
  } else {
    const Grading grading{.kind = GradingKind::kSieve, .sieve = rows};
    const std::string fines = rows.front().percent_passing > 0.0
                                  ? trs(Text::kSieveFines, rows.front().percent_passing)
                                  : std::string();
    ImGui::TextDisabled(
        "%s", trf(Text::kSieveRange, smallest_size(grading), largest_size(grading), fines).c_str());
  }
  ImGui::PopTextWrapPos();
}

}  // namespace aggpack::gui
