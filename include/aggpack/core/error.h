#pragma once
// The one exception hierarchy of aggpack. Every public entry point validates its input and throws
// one of these; the CLI turns them into a one-line message and a non-zero exit code.

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "aggpack/core/error_words.h"

namespace aggpack {

/// What went wrong, for callers that branch on it (one test per kind).
enum class ErrorKind {
  kInvalidInput,  ///< a parameter or config value outside its allowed range
  kIoError,       ///< a file could not be read or written
  kFormatError,   ///< a file was read but its content is wrong (truncated, corrupt, wrong version)
  kLimitExceeded  ///< a computation would exceed a set cap (vertex cap, attempt budget)
};

/// A value of an error's parts that is a sentence of its own (the first skipped mesh file's
/// reason inside "all 3 were skipped; first: ..."): its text in the message, and its wording.
struct WordedValue {
  std::string text;
  Wording wording;
};

/// Base of all aggpack exceptions. Besides its English message, an error carries its parts
/// (error_words.h), so a front end words it in its own language without parsing the text: the
/// field, value and allowed wording of a refused value (has_value()), else the whole message's
/// wording.
class Error : public std::runtime_error {
 public:
  /// A free-form message: its wording is Sentence::kText of the message.
  Error(ErrorKind kind, const std::string& message)
      : std::runtime_error(message), kind_(kind), wording_{Sentence::kText, {message}} {}
  /// A message in one sentence (english(wording)).
  Error(ErrorKind kind, Wording wording)
      : std::runtime_error(english(wording)), kind_(kind), wording_(std::move(wording)) {}
  [[nodiscard]] ErrorKind kind() const { return kind_; }
  /// True when the error refuses one value: field(), value() and wording() (the allowed part).
  [[nodiscard]] bool has_value() const { return has_value_; }
  /// The field or key at fault ("" unless has_value()).
  [[nodiscard]] const std::string& field() const { return field_; }
  /// The refused value as text ("" unless has_value()).
  [[nodiscard]] const std::string& value() const { return value_; }
  /// The field in words: Sentence::kText of field() unless the field is a phrase ("particles 3
  /// and 5").
  [[nodiscard]] const Wording& field_wording() const { return field_wording_; }
  /// The value in words: Sentence::kText of value() unless the value is a phrase ("0.1 mm apart").
  [[nodiscard]] const Wording& value_wording() const { return value_wording_; }
  /// has_value(): what is allowed; else the whole message.
  [[nodiscard]] const Wording& wording() const { return wording_; }
  /// Values of the parts above that are sentences of their own: a front end words a value
  /// equal to one's text as its wording. Empty for most errors.
  [[nodiscard]] const std::vector<WordedValue>& worded_values() const { return worded_values_; }
  /// Marks `text`, a value of this error's parts, as the sentence `wording` (before throwing).
  void word_value(std::string text, Wording wording) {
    worded_values_.push_back({std::move(text), std::move(wording)});
  }

 protected:
  /// A refused value: `message` is the English sentence around field, value and allowed.
  Error(ErrorKind kind, const std::string& message, std::string field, std::string value,
        Wording allowed)
      : std::runtime_error(message),
        kind_(kind),
        has_value_(true),
        field_(std::move(field)),
        value_(std::move(value)),
        wording_(std::move(allowed)),
        field_wording_{Sentence::kText, {field_}},
        value_wording_{Sentence::kText, {value_}} {}
  /// A refused value whose field and value are phrases in words.
  Error(ErrorKind kind, const std::string& message, Wording field, Wording value, Wording allowed)
      : Error(kind, message, english(field), english(value), std::move(allowed)) {
    field_wording_ = std::move(field);
    value_wording_ = std::move(value);
  }

 private:
  ErrorKind kind_;
  bool has_value_ = false;
  std::string field_;
  std::string value_;
  Wording wording_;
  Wording field_wording_;
  Wording value_wording_;
  std::vector<WordedValue> worded_values_;
};

/// A parameter outside its allowed range. The message names the field, the value and the range:
/// "invalid FIELD = VALUE (allowed: ALLOWED)".
class InvalidInput : public Error {
 public:
  InvalidInput(const std::string& field, const std::string& value, const std::string& allowed)
      : InvalidInput(field, value, Wording{Sentence::kText, {allowed}}) {}
  InvalidInput(const std::string& field, const std::string& value, Wording allowed)
      : Error(ErrorKind::kInvalidInput,
              "invalid " + field + " = " + value + " (allowed: " + english(allowed) + ")", field,
              value, allowed) {}
  /// A field and value that are phrases ("particles 3 and 5" = "0.1 mm apart").
  InvalidInput(Wording field, Wording value, Wording allowed)
      : Error(ErrorKind::kInvalidInput,
              "invalid " + english(field) + " = " + english(value) +
                  " (allowed: " + english(allowed) + ")",
              field, value, allowed) {}
  /// The allowed text in English.
  [[nodiscard]] std::string allowed() const { return english(wording()); }
};

/// A file that cannot be opened, created or renamed.
class IoError : public Error {
 public:
  explicit IoError(const std::string& message) : Error(ErrorKind::kIoError, message) {}
  explicit IoError(Wording wording) : Error(ErrorKind::kIoError, std::move(wording)) {}
};

/// A file whose content is not what it should be.
class FormatError : public Error {
 public:
  explicit FormatError(const std::string& message) : Error(ErrorKind::kFormatError, message) {}
  explicit FormatError(Wording wording) : Error(ErrorKind::kFormatError, std::move(wording)) {}
};

/// A computation that would exceed a configured cap:
/// "limit exceeded for FIELD = VALUE (allowed: ALLOWED)".
class LimitExceeded : public Error {
 public:
  LimitExceeded(const std::string& field, const std::string& value, const std::string& allowed)
      : LimitExceeded(field, value, Wording{Sentence::kText, {allowed}}) {}
  LimitExceeded(const std::string& field, const std::string& value, Wording allowed)
      : Error(
            ErrorKind::kLimitExceeded,
            "limit exceeded for " + field + " = " + value + " (allowed: " + english(allowed) + ")",
            field, value, allowed) {}
  /// A field and value that are phrases ("mesomodel mesh" = "TetGen moved ...").
  LimitExceeded(Wording field, Wording value, Wording allowed)
      : Error(ErrorKind::kLimitExceeded,
              "limit exceeded for " + english(field) + " = " + english(value) +
                  " (allowed: " + english(allowed) + ")",
              field, value, allowed) {}
};

/// `error` quoted as a value of another error's sentence ("not a polyhedron: invalid ..."): first
/// its message with its whole wording, then the values its parts need worded (to pass to
/// Error::word_value of the error that quotes it).
std::vector<WordedValue> worded_as_value(const Error& error);

/// Formats a double for error messages with enough digits to be unambiguous.
std::string format_value(double value);

/// Throws InvalidInput unless lo <= value <= hi and value is finite.
void require_in_range(const std::string& field, double value, double lo, double hi);

/// Throws InvalidInput unless value is finite and > 0.
void require_positive(const std::string& field, double value);

}  // namespace aggpack
