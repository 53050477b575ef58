#include "aggpack/core/error.h"

#include <cmath>
#include <cstddef>
#include <cstdio>
#include <iterator>

namespace aggpack {

std::string format_value(double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.10g", value);
  return buffer;
}

void require_in_range(const std::string& field, double value, double lo, double hi) {
  if (!std::isfinite(value) || value < lo || value > hi) {
    throw InvalidInput(field, format_value(value),
                       "[" + format_value(lo) + ", " + format_value(hi) + "]");
  }
}

void require_positive(const std::string& field, double value) {
  if (!std::isfinite(value) || value <= 0.0) {
    throw InvalidInput(field, format_value(value), Wording{Sentence::kFinitePositive, {}});
  }
}

std::vector<WordedValue> worded_as_value(const Error& error) {
  std::vector<WordedValue> words;
  if (!error.has_value()) {
    words.push_back({error.what(), error.wording()});
  } else {
    const Sentence sentence =
        error.kind() == ErrorKind::kLimitExceeded ? Sentence::kLimitValue : Sentence::kInvalidValue;
    words.push_back(
        {error.what(), {sentence, {error.field(), error.value(), english(error.wording())}}});
    for (const Wording* part : {&error.field_wording(), &error.value_wording(), &error.wording()}) {
      if (part->sentence != Sentence::kText) words.push_back({english(*part), *part});
    }
  }
  words.insert(words.end(), error.worded_values().begin(), error.worded_values().end());
  return words;
}

}  // namespace aggpack

namespace aggpack {

const char* english_words(Sentence sentence) {
  static constexpr const char* kWords[] = {
#define AGGPACK_SENTENCE_WORDS(name, english) english,
      // One entry per sentence; a long one is several literals joined on purpose (error_words.h).
      // NOLINTNEXTLINE(bugprone-suspicious-missing-comma)
      AGGPACK_ERROR_SENTENCES(AGGPACK_SENTENCE_WORDS)
#undef AGGPACK_SENTENCE_WORDS
  };
  const auto index = static_cast<std::size_t>(sentence);
  return index < std::size(kWords) ? kWords[index] : "{}";
}

std::string fill_words(const char* words, const std::vector<std::string>& values) {
  std::string text;
  std::size_t next = 0;
  for (const char* at = words; *at != '\0'; ++at) {
    if (at[0] == '{' && at[1] == '}' && next < values.size()) {
      text += values[next++];
      ++at;
    } else {
      text += *at;
    }
  }
  return text;
}

}  // namespace aggpack
