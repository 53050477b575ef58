#include "library_words.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <filesystem>
#include <new>
#include <string_view>
#include <system_error>

#include "aggpack/config/config.h"
#include "aggpack/config/schema.h"
#include "aggpack/core/error.h"
#include "aggpack/core/text.h"
#include "aggpack/pipeline/pipeline.h"
#include "system_words.h"

namespace aggpack::gui {

namespace {

// Every sentence's entry: a sentence without one is a compile error here (no kSentence<Name>).
constexpr std::array<Text, static_cast<std::size_t>(Sentence::kCount)> kSentenceTexts = {{
#define AGGPACK_SENTENCE_TEXT(name, english) Text::kSentence##name,
    AGGPACK_ERROR_SENTENCES(AGGPACK_SENTENCE_TEXT)
#undef AGGPACK_SENTENCE_TEXT
}};

// A free-form message without the origin the panel is ("gui: ", "defaults: ", "--set K=V: ").
std::string without_origin(std::string message) {
  for (const std::string_view prefix :
       {std::string_view("gui: "), std::string_view("defaults: ")}) {
    if (message.rfind(prefix, 0) == 0) message.erase(0, prefix.size());
  }
  if (message.rfind("--set ", 0) == 0) {
    const auto colon = message.find(": ");
    if (colon != std::string::npos) message.erase(0, colon + 2);
  }
  return message;
}

Text stop_text(StopReason reason) {
  switch (reason) {
    case StopReason::kTargetReached:
      return Text::kStopTarget;
    case StopReason::kAttemptBudget:
      return Text::kStopBudget;
    case StopReason::kConsecutiveFailures:
      return Text::kStopFailures;
    case StopReason::kSizeListExhausted:
      return Text::kStopSizeList;
    case StopReason::kCancelled:
      return Text::kStopCancelled;
  }
  return Text::kStopTarget;
}

Text densify_stop_text(DensifyStop stop) {
  switch (stop) {
    case DensifyStop::kTargetReached:
      return Text::kStopTarget;
    case DensifyStop::kSettled:
      return Text::kDensifySettled;
    case DensifyStop::kJammed:
      return Text::kDensifyJammed;
    case DensifyStop::kSweepBudget:
      return Text::kDensifySweepBudget;
    case DensifyStop::kTimeBudget:
      return Text::kDensifyTimeBudget;
    case DensifyStop::kCancelled:
      return Text::kStopCancelled;
  }
  return Text::kStopTarget;
}

// The sentences named Phrase*: a value that is one of them is worded too ("directory").
constexpr std::array<bool, static_cast<std::size_t>(Sentence::kCount)> kIsPhrase = {{
#define AGGPACK_SENTENCE_IS_PHRASE(name, english) std::string_view(#name).rfind("Phrase", 0) == 0,
    AGGPACK_ERROR_SENTENCES(AGGPACK_SENTENCE_IS_PHRASE)
#undef AGGPACK_SENTENCE_IS_PHRASE
}};

// A value in the window's language: a phrase's words, an operating-system reason's words
// (system_words.h), anything else (a number, a file or key name) as it is. A phrase naming an
// options field is matched, and worded, with the configuration key's name (as with_key_names
// renames it in the error).
std::string value_words(const std::string& value) {
  if (std::string system = system_reason_words(value); !system.empty()) return system;
  const auto& schema = pack_schema();
  static const std::vector<KeyView> keys = key_views(schema);
  for (std::size_t k = 0; k < kIsPhrase.size(); ++k) {
    if (!kIsPhrase[k]) continue;
    const std::string english = english_words(static_cast<Sentence>(k));
    if (value == english) return tr(kSentenceTexts[k]);
    if (value == to_key_names(keys, schema.aliases, english)) {
      return to_key_names(keys, schema.aliases, tr(kSentenceTexts[k]));
    }
  }
  return value;
}

// A field of the solver deck's panel by the name the library gives it ("baffle position"): its
// label there ("挡板位置 m"), without the widget id.
std::string field_words(const Wording& field) {
  struct DeckLabel {
    std::string_view field;
    Text label;
  };
  static constexpr DeckLabel kLabels[] = {
      {"friction", Text::kDeckFriction},
      {"gravity", Text::kDeckGravity},
      {"baffle speed", Text::kDeckBaffleSpeed},
      {"baffle position", Text::kDeckBafflePosition},
      {"trough length", Text::kDeckTroughLength},
      {"settle time", Text::kDeckSettle},
      {"rest time", Text::kDeckRest},
      {"density", Text::kDeckDensity},
      {"youngs modulus", Text::kDeckYoungs},
      {"poisson ratio", Text::kDeckPoisson},
      {"contact distance", Text::kDeckContact},
      {"time step", Text::kDeckTimeStep},
  };
  if (field.sentence == Sentence::kText && field.values.size() == 1) {
    for (const DeckLabel& deck : kLabels) {
      if (field.values.front() != deck.field) continue;
      const std::string label = tr(deck.label);
      return label.substr(0, label.find("##"));
    }
  }
  return wording_words(field);
}

}  // namespace

Text sentence_text(Sentence sentence) {
  const auto index = static_cast<std::size_t>(sentence);
  return index < kSentenceTexts.size() ? kSentenceTexts[index] : Text::kSentenceText;
}

std::string wording_words(const Wording& wording) { return wording_words(wording, {}); }

std::string wording_words(const Wording& wording, const std::vector<WordedValue>& worded) {
  std::vector<std::string> values;
  values.reserve(wording.values.size());
  for (const std::string& value : wording.values) {
    const auto sentence = std::find_if(worded.begin(), worded.end(),
                                       [&](const WordedValue& each) { return each.text == value; });
    if (sentence == worded.end()) {
      values.push_back(value_words(value));
      continue;
    }
    // Its own values may be sentences too (the others: each is worded once, so no loop).
    std::vector<WordedValue> others;
    for (const WordedValue& each : worded) {
      if (&each != &*sentence) others.push_back(each);
    }
    values.push_back(wording_words(sentence->wording, others));
  }
  return fill_words(tr(sentence_text(wording.sentence)), values);
}

std::string error_words(const std::exception& error) {
  const auto* library = dynamic_cast<const Error*>(&error);
  if (library == nullptr) {
    // Not the library's: out of memory, an operating-system failure (its reason as it is), or a
    // bug (the library checks its input and throws its own errors).
    if (dynamic_cast<const std::bad_alloc*>(&error) != nullptr) return tr(Text::kErrorOutOfMemory);
    if (const auto* system = dynamic_cast<const std::system_error*>(&error)) {
      if (language() == Language::kEnglish) return trs(Text::kErrorOther, error.what());
      // The reason in words, and the paths a file-system error names.
      std::string reason = system_reason_words(system->code());
      if (const auto* file = dynamic_cast<const std::filesystem::filesystem_error*>(&error)) {
        for (const auto* path : {&file->path1(), &file->path2()}) {
          if (!path->empty()) reason += trs(Text::kErrorPath, path->string());
        }
      }
      return trs(Text::kErrorOther, reason);
    }
    return trs(Text::kErrorInternal, error.what());
  }
  if (library->has_value()) {
    return trs(
        library->kind() == ErrorKind::kLimitExceeded ? Text::kLimitNotAllowed : Text::kNotAllowed,
        field_words(library->field_wording()),
        wording_words(library->value_wording(), library->worded_values()),
        wording_words(library->wording(), library->worded_values()));
  }
  if (library->wording().sentence == Sentence::kText) return without_origin(error.what());
  return wording_words(library->wording(), library->worded_values());
}

std::string allowed_words(const KeyView& key) {
  const bool has_note = has_words(*key.note);
  if (key.type == ValueType::kPath && has_note) return wording_words(*key.note);
  std::string text = wording_words(allowed_rule(key));
  if (has_note) text += tr(Text::kListSeparator) + wording_words(*key.note);
  return text;
}

std::string default_words(const KeyView& key, const Value& default_value,
                          const std::string& default_from, const Wording& shown) {
  if (has_words(shown)) return wording_words(shown);
  return default_text(key, default_value, default_from, shown);
}

std::string report_words(const PackReport& report) {
  return trs(Text::kReportSummary, report.placed, report.requested, report.rejected,
             report.solid_volume, report.container_volume, 100.0 * report.solid_fraction,
             tr(stop_text(report.stop_reason)));
}

std::string densify_words(const DensifyReport& report) {
  const std::string bulk =
      report.bulk_fraction > 0.0 ? trs(Text::kDensifyBulk, report.bulk_fraction) : std::string();
  return trs(Text::kDensifySummary, report.start_fraction, report.solid_fraction, bulk,
             report.sweeps, format_seconds(report.seconds), tr(densify_stop_text(report.stop)));
}

std::vector<std::string> shortfall_words(const PipelineResult& result) {
  std::vector<std::string> lines;
  for (const DenseShortfall kind : dense_shortfall_kinds(result)) {
    switch (kind) {
      case DenseShortfall::kCancelled:
        lines.emplace_back(tr(Text::kShortfallCancelled));
        break;
      case DenseShortfall::kFillBelowTarget: {
        const PackReport& fill = result.fill->report;
        lines.push_back(trs(Text::kShortfallFill, fill.solid_fraction, fill.target_solid_fraction,
                            tr(stop_text(fill.stop_reason)), result.report.solid_fraction,
                            result.fill->asked_fraction));
        break;
      }
      case DenseShortfall::kDensifyStopped:
        lines.push_back(trs(Text::kShortfallDensify, densify_words(*result.densify)));
        break;
      case DenseShortfall::kContainerLarger:
        lines.back() += trs(Text::kShortfallLarger, result.packing.container.volume(),
                            result.fill->given.volume());
        break;
    }
  }
  return lines;
}

}  // namespace aggpack::gui
