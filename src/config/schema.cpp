// The schema's target-independent half: range and value text for messages, the writer and the
// docs, and the translation of validator field names to key names. Reading TOML is reader.cpp.

#include "aggpack/config/schema.h"

#include <fmt/core.h>

#include <cctype>
#include <charconv>
#include <cmath>

#include "aggpack/core/text.h"

namespace aggpack {

namespace {

std::string format_double(double value) {
  // Shortest round-trip text; plain decimals ("0.0005") unless they get long (1e-12, 3e+20).
  char buffer[512];
  auto result = std::to_chars(buffer, buffer + sizeof buffer, value, std::chars_format::fixed);
  std::string text(buffer, result.ptr);
  if (result.ec != std::errc() || text.size() > 12) {
    result = std::to_chars(buffer, buffer + sizeof buffer, value);
    text.assign(buffer, result.ptr);
  }
  // TOML needs a float to look like one ("3" is an integer).
  if (text.find_first_of(".eEn") == std::string::npos) text += ".0";
  return text;
}

std::string bound_text(double value, const char* text) {
  if (text != nullptr) return text;
  const double exponent = std::log10(std::abs(value));
  if (value >= 1e5 && exponent == std::floor(exponent)) {
    return "1e" + std::to_string(static_cast<int>(exponent));
  }
  return fmt::format("{}", value);
}

bool is_name_char(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_' || c == '.';
}

}  // namespace

bool Range::contains(double value) const {
  return std::isfinite(value) && (lo_end == End::kOpen ? value > lo : value >= lo) &&
         (hi_end == End::kOpen ? value < hi : value <= hi);
}

std::string Range::text() const {
  return (lo_end == End::kOpen ? "(" : "[") + bound_text(lo, nullptr) + ", " +
         bound_text(hi, hi_text) + (hi_end == End::kOpen ? ")" : "]");
}

Wording allowed_rule(const KeyView& key) {
  std::string text;
  switch (key.type) {
    case ValueType::kWord:
      for (const auto& word : *key.words) text += (text.empty() ? "" : " | ") + word;
      break;
    case ValueType::kBool:
      text = "true | false";
      break;
    case ValueType::kPath:
      return {Sentence::kNonEmptyPath, {}};
    case ValueType::kPathList:
      return {Sentence::kNonEmptyPathList, {}};
    default:
      text = key.range->text();
  }
  return {Sentence::kText, {text}};
}

std::string allowed_text(const KeyView& key) {
  // A string that is not a path says what it is.
  if (key.type == ValueType::kPath && has_words(*key.note)) return english(*key.note);
  std::string text = english(allowed_rule(key));
  if (has_words(*key.note)) text += ", " + english(*key.note);
  return text;
}

const char* type_name(ValueType type) {
  switch (type) {
    case ValueType::kFloat:
      return "float";
    case ValueType::kInteger:
      return "integer";
    case ValueType::kBool:
      return "boolean";
    case ValueType::kNumberList:
    case ValueType::kSieve:
      return "array";
    case ValueType::kWord:
    case ValueType::kPath:
      return "string";
    case ValueType::kPathList:
      return "string or array";
  }
  return "";
}

std::string value_text(const Value& value, ValueType type, WriteStyle style) {
  const auto number = [style](double x) {
    return style == WriteStyle::kCanonical ? format_double(x) : fmt::format("{}", x);
  };
  switch (type) {
    case ValueType::kFloat:
      return number(std::get<double>(value));
    case ValueType::kInteger:
      return std::to_string(std::get<std::int64_t>(value));
    case ValueType::kWord:
    case ValueType::kPath:
      return aggpack::quoted(std::get<std::string>(value));
    case ValueType::kPathList: {
      // One path is written as a string, as it is usually typed.
      const auto& paths = std::get<std::vector<std::string>>(value);
      if (paths.size() == 1) return aggpack::quoted(paths.front());
      std::string text = "[";
      for (const std::string& path : paths) {
        text += (text.size() > 1 ? ", " : "") + aggpack::quoted(path);
      }
      return text + "]";
    }
    case ValueType::kBool:
      return std::get<bool>(value) ? "true" : "false";
    case ValueType::kNumberList: {
      std::string text = "[";
      for (const double x : std::get<std::vector<double>>(value)) {
        text += (text.size() > 1 ? ", " : "") + number(x);
      }
      return text + "]";
    }
    case ValueType::kSieve: {
      const auto& rows = std::get<std::vector<SieveRow>>(value);
      std::string text = "[";
      for (std::size_t r = 0; r < rows.size(); ++r) {
        text += (r == 0 ? "[" : ", [") + number(rows[r].size) + ", " +
                number(rows[r].percent_passing) + "]";
      }
      return text + "]";
    }
  }
  return "";
}

std::string default_text(const KeyView& key, const Value& default_value,
                         const std::string& default_from, const Wording& shown) {
  if (has_words(shown)) return english(shown);
  if (!default_from.empty()) return "= `" + default_from + "`";
  return "`" + value_text(default_value, key.type, WriteStyle::kCanonical) + "`";
}

void fail_key(const GivenValues& given, const std::string& key, const std::string& message) {
  const auto found = given.find(key);
  const std::string where = found != given.end() ? found->second.origin + ": " : "";
  throw ConfigError(key, where + message);
}

void fail_key(const GivenValues& given, const std::string& key, const std::string& field,
              const std::string& value, const Wording& allowed) {
  const auto found = given.find(key);
  const std::string where = found != given.end() ? found->second.origin + ": " : "";
  throw ConfigError(key, where, field, value, allowed);
}

std::string to_key_names(const std::vector<KeyView>& keys,
                         const std::map<std::string, std::string>& aliases, std::string message) {
  std::map<std::string, std::string> names = aliases;
  for (const auto& key : keys) {
    for (const auto& field : *key.fields) names.emplace(field, *key.name);
  }
  // The field a message is about ("invalid friction = ...", "limit exceeded for edge_length =
  // ..."), bare or dotted.
  for (const std::string lead : {"invalid ", "limit exceeded for "}) {
    if (message.rfind(lead, 0) != 0) continue;
    const auto end = message.find(" = ", lead.size());
    if (end == std::string::npos) break;
    const auto found = names.find(message.substr(lead.size(), end - lead.size()));
    if (found != names.end()) message = lead + found->second + message.substr(end);
    break;
  }
  // Dotted field names anywhere else ("allowed: 0 or >= lattice.radius").
  for (const auto& [field, key] : names) {
    if (field.find('.') == std::string::npos || field == key) continue;
    for (auto at = message.find(field); at != std::string::npos; at = message.find(field, at)) {
      const auto after = at + field.size();
      const bool is_whole =
          (at == 0 || !is_name_char(message[at - 1])) &&
          (after == message.size() || message[after] == '.' || !is_name_char(message[after]));
      if (!is_whole) {
        at = after;
        continue;
      }
      message.replace(at, field.size(), key);
      at += key.size();
    }
  }
  return message;
}

void with_key_names(const std::vector<KeyView>& keys,
                    const std::map<std::string, std::string>& aliases,
                    const std::function<void()>& check) {
  // A name in the error's parts, renamed ("lattice.radius" -> the key), as in its message.
  auto renamed = [&](const std::string& name) {
    const std::string lead = to_key_names(keys, aliases, "invalid " + name + " = ");
    return lead.substr(8, lead.size() - 11);
  };
  auto renamed_wording = [&](Wording wording) {
    for (std::string& value : wording.values) value = to_key_names(keys, aliases, value);
    return wording;
  };
  // A field or value in words of its own ("sizes from 0.001 m") is kept as it is when the
  // message names no field to rename.
  auto is_phrase = [&](const Error& error) {
    return (error.field_wording().sentence != Sentence::kText ||
            error.value_wording().sentence != Sentence::kText) &&
           to_key_names(keys, aliases, error.what()) == error.what();
  };
  try {
    check();
  } catch (const InvalidInput& error) {
    if (is_phrase(error)) throw;
    const std::string key = renamed(error.field());
    ConfigError renamed_error(key, "", key, error.value(), renamed_wording(error.wording()));
    // The message as before (also the names within the allowed text's own words).
    if (renamed_error.what() != to_key_names(keys, aliases, error.what())) {
      throw ConfigError(renamed(error.field()), to_key_names(keys, aliases, error.what()));
    }
    throw renamed_error;
  } catch (const LimitExceeded& error) {
    if (is_phrase(error)) throw;
    LimitExceeded renamed_error(renamed(error.field()), error.value(),
                                renamed_wording(error.wording()));
    if (renamed_error.what() != to_key_names(keys, aliases, error.what())) {
      throw Error(error.kind(), to_key_names(keys, aliases, error.what()));
    }
    throw renamed_error;
  } catch (const Error& error) {
    if (error.kind() != ErrorKind::kInvalidInput && error.kind() != ErrorKind::kLimitExceeded) {
      throw;
    }
    // A message in one sentence keeps it, its values renamed, when that words the same message.
    const std::string message = to_key_names(keys, aliases, error.what());
    if (!error.has_value() && error.wording().sentence != Sentence::kText) {
      Error renamed_error(error.kind(), renamed_wording(error.wording()));
      if (renamed_error.what() == message) throw renamed_error;
    }
    throw Error(error.kind(), message);
  }
}

}  // namespace aggpack
