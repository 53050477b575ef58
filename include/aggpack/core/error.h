#pragma once
// The one exception hierarchy of aggpack. Every public entry point validates its input and throws
// one of these; the CLI turns them into a one-line message and a non-zero exit code.

#include <stdexcept>
#include <string>

namespace aggpack {

/// What went wrong, for callers that branch on it (one test per kind).
enum class ErrorKind {
  kInvalidInput,  ///< a parameter or config value outside its allowed range
  kIoError,       ///< a file could not be read or written
  kFormatError,   ///< a file was read but its content is wrong (truncated, corrupt, wrong version)
  kLimitExceeded  ///< a computation would exceed a set cap (vertex cap, attempt budget)
};

/// Base of all aggpack exceptions.
class Error : public std::runtime_error {
 public:
  Error(ErrorKind kind, const std::string& message) : std::runtime_error(message), kind_(kind) {}
  [[nodiscard]] ErrorKind kind() const { return kind_; }

 private:
  ErrorKind kind_;
};

/// A parameter outside its allowed range. The message names the field, the value and the range.
class InvalidInput : public Error {
 public:
  InvalidInput(const std::string& field, const std::string& value, const std::string& allowed)
      : Error(ErrorKind::kInvalidInput,
              "invalid " + field + " = " + value + " (allowed: " + allowed + ")"),
        field_(field),
        allowed_(allowed) {}
  [[nodiscard]] const std::string& field() const { return field_; }
  /// The allowed text, for a front end that names the field in the user's words.
  [[nodiscard]] const std::string& allowed() const { return allowed_; }

 private:
  std::string field_;
  std::string allowed_;
};

/// A file that cannot be opened, created or renamed.
class IoError : public Error {
 public:
  explicit IoError(const std::string& message) : Error(ErrorKind::kIoError, message) {}
};

/// A file whose content is not what it should be.
class FormatError : public Error {
 public:
  explicit FormatError(const std::string& message) : Error(ErrorKind::kFormatError, message) {}
};

/// A computation that would exceed a configured cap.
class LimitExceeded : public Error {
 public:
  LimitExceeded(const std::string& field, const std::string& value, const std::string& allowed)
      : Error(ErrorKind::kLimitExceeded,
              "limit exceeded for " + field + " = " + value + " (allowed: " + allowed + ")") {}
};

/// Formats a double for error messages with enough digits to be unambiguous.
std::string format_value(double value);

/// Throws InvalidInput unless lo <= value <= hi and value is finite.
void require_in_range(const std::string& field, double value, double lo, double hi);

/// Throws InvalidInput unless value is finite and > 0.
void require_positive(const std::string& field, double value);

}  // namespace aggpack
