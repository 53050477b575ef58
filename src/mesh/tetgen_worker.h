// Internal: how a TetGen worker process answers (tetgen.cpp per particle, mesomodel_tetgen.cpp for
// a whole specimen). The answer is 'M' and the result's bytes (arrays as they are in memory:
// parent and worker are the same program), or 'F' and what TetGen reported, then (when it has
// them) its words: NUL, the sentence's number, and NUL before each value (core/error_words.h;
// the same program, so the same numbers).
#pragma once

#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

#include "aggpack/core/error.h"
#include "aggpack/core/isolated.h"

namespace aggpack::detail {

/// What TetGen did wrong, as the worker reports it, and in words (none: `what` only).
struct TetGenFailure {
  std::string what;
  Wording wording{};
};

/// A failure in words (its English is `what`).
inline TetGenFailure tetgen_failure(Wording wording) {
  std::string what = english(wording);
  return {std::move(what), std::move(wording)};
}

/// Appends the array's bytes as they are in memory.
template <class T>
void append_array(std::string& out, const std::vector<T>& values) {
  out.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
}

/// The worker's answer for `mesh()` (the result's bytes; may throw TetGenFailure).
template <class Mesh>
std::string worker_answer(const Mesh& mesh) {
  try {
    return 'M' + mesh();
  } catch (const TetGenFailure& failure) {
    std::string answer = 'F' + failure.what;
    if (has_words(failure.wording)) {
      answer += '\0' + std::to_string(static_cast<int>(failure.wording.sentence));
      for (const std::string& value : failure.wording.values) answer += '\0' + value;
    }
    return answer;
  }
}

/// The result's bytes of an answered outcome, or false with `failure` saying why not in words
/// ("TetGen died of signal 6 (Aborted)", TetGen's own report, or a malformed answer), and
/// `words`: values of it that are sentences of their own (Error::worded_values).
inline bool worker_result(const IsolatedOutcome& outcome, std::string& bytes, Wording& failure,
                          std::vector<WordedValue>& words) {
  if (!outcome.is_done) {
    failure = {Sentence::kTetGenWorker, {outcome.failure}};
    if (has_words(outcome.failure_wording)) {
      words.push_back({outcome.failure, outcome.failure_wording});
    }
    return false;
  }
  if (!outcome.bytes.empty() && outcome.bytes[0] == 'F') {
    const std::string answer = outcome.bytes.substr(1);
    const auto end = answer.find('\0');
    failure = {Sentence::kText, {answer.substr(0, end)}};
    if (end == std::string::npos) return false;
    std::vector<std::string> parts;
    for (std::size_t at = end + 1;;) {
      const auto next = answer.find('\0', at);
      parts.push_back(answer.substr(at, next == std::string::npos ? next : next - at));
      if (next == std::string::npos) break;
      at = next + 1;
    }
    const int sentence = std::atoi(parts.front().c_str());
    if (sentence > 0 && sentence < static_cast<int>(Sentence::kCount)) {
      Wording words_of_it{static_cast<Sentence>(sentence),
                          std::vector<std::string>(parts.begin() + 1, parts.end())};
      // Taken only when its English is the report (a stale or foreign number is not).
      if (english(words_of_it) == failure.values.front()) failure = std::move(words_of_it);
    }
    return false;
  }
  if (outcome.bytes.empty() || outcome.bytes[0] != 'M') {
    failure = {Sentence::kWorkerMalformed, {}};
    return false;
  }
  bytes = outcome.bytes.substr(1);
  return true;
}

/// The result's bytes of an answered outcome, or false with `failure` saying why not ("TetGen
/// died of signal 6 (Aborted)", TetGen's own report, or a malformed answer).
inline bool worker_result(const IsolatedOutcome& outcome, std::string& bytes,
                          std::string& failure) {
  Wording wording;
  std::vector<WordedValue> words;
  const bool is_answered = worker_result(outcome, bytes, wording, words);
  if (!is_answered) failure = english(wording);
  return is_answered;
}

}  // namespace aggpack::detail
