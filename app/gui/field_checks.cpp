// The panel's field checks (each number against its range, then the rules between fields, in
// plain words beside the field), what changed since the shown packing, and the scripted --edit.

#include <fmt/core.h>

#include <algorithm>
#include <map>
#include <string>
#include <vector>

#include "aggpack/core/error.h"
#include "gui_app.h"
#include "i18n.h"
#include "library_words.h"

namespace aggpack::gui {

bool GuiApp::is_result_stale() const {
  return packing_ != nullptr && !upload_.is_pending() && last_entries_ != packing_entries_;
}

std::vector<std::string> GuiApp::changed_keys() const {
  auto as_map = [](const std::vector<std::string>& entries) {
    std::map<std::string, std::string> map;
    for (const std::string& entry : entries) {
      const auto equals = entry.find('=');
      map[entry.substr(0, equals)] = equals == std::string::npos ? "" : entry.substr(equals + 1);
    }
    return map;
  };
  const auto now = as_map(last_entries_), then = as_map(packing_entries_);
  std::vector<std::string> keys;
  for (const auto& [key, value] : now) {
    const auto found = then.find(key);
    if (found == then.end() || found->second != value) keys.push_back(key);
  }
  for (const auto& [key, value] : then) {
    if (now.count(key) == 0) keys.push_back(key);
  }
  return keys;
}

void GuiApp::update_field_errors() {
  std::vector<std::string> entries = fields_.set_entries();
  if (entries == last_entries_ && !last_entries_.empty()) return;
  last_entries_ = std::move(entries);
  field_errors_.clear();
  form_error_.clear();
  // Each shown number against its range, in plain words next to the field.
  const auto& schema = pack_schema();
  const auto views = key_views(schema);
  const PackConfig draft = fields_.draft();
  for (std::size_t i = 0; i < schema.keys.size(); ++i) {
    const auto& key = schema.keys[i];
    if (!ConfigFields::is_editable(key) || !key.scope(draft)) continue;
    if (key.presence == Presence::kOptional && !fields_.is_on(key.name)) continue;
    const Value& value = fields_.value(key.name);
    double number = 0.0;
    if (key.type == ValueType::kFloat) {
      number = std::get<double>(value);
    } else if (key.type == ValueType::kInteger) {
      number = static_cast<double>(std::get<std::int64_t>(value));
    } else {
      continue;
    }
    if (key.range.contains(number)) continue;
    const std::string unit = key.unit.empty() || key.unit == "-" ? "" : " " + key.unit;
    field_errors_[key.name] =
        trs(Text::kOutsideRange, format_value(number), allowed_words(views[i]), unit);
  }
  if (!field_errors_.empty()) return;
  // Then the rules between fields, with the configuration's own message for the field it names.
  try {
    (void)fields_.build();
  } catch (const ConfigError& error) {
    // Worded from the error's parts (library_words.h); beside its field without the key.
    const std::string words = error_words(error);
    std::string message = words;
    const std::string prefix = error.key() + tr(Text::kKeySeparator);
    if (message.rfind(prefix, 0) == 0) message.erase(0, prefix.size());
    if (error.key().empty() || !fields_.has(error.key())) {
      form_error_ = words;
    } else {
      field_errors_[error.key()] = message;
    }
  } catch (const Error& error) {
    form_error_ = error_words(error);
  }
}

void GuiApp::apply_edits() {
  const auto& keys = pack_schema().keys;
  for (const std::string& edit : options_.edits) {
    const auto equals = edit.find('=');
    const std::string name = edit.substr(0, equals);
    const std::string text = equals == std::string::npos ? "" : edit.substr(equals + 1);
    const auto key =
        std::find_if(keys.begin(), keys.end(), [&](const auto& k) { return k.name == name; });
    if (key == keys.end() || !fields_.has(name) || equals == std::string::npos) {
      std::fprintf(stderr, "aggpack-gui: error: --edit %s: no such field in the panel\n",
                   edit.c_str());
      exit_code_ = 2;
      continue;
    }
    Value& value = fields_.value(name);
    try {
      switch (key->type) {
        case ValueType::kFloat:
          value = std::stod(text);
          break;
        case ValueType::kInteger:
          value = static_cast<std::int64_t>(std::stoll(text));
          break;
        case ValueType::kBool:
          value = text == "true";
          break;
        case ValueType::kWord: {
          std::string word = text;
          if (word.size() >= 2 && word.front() == '"' && word.back() == '"') {
            word = word.substr(1, word.size() - 2);
          }
          value = word;
          break;
        }
        default:
          throw InvalidInput("--edit", edit, "a number, word or true/false field");
      }
      if (key->presence == Presence::kOptional) fields_.set_on(name, true);
    } catch (const std::exception&) {
      std::fprintf(stderr, "aggpack-gui: error: --edit %s: not a value for this field\n",
                   edit.c_str());
      exit_code_ = 2;
    }
  }
  update_field_errors();
}

}  // namespace aggpack::gui
