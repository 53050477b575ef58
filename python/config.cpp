// aggpack.PackConfig: the pack configuration of `aggpack pack` (aggpack/config/config.h), built
// from TOML text, a file or a dict. Every check is the config module's own: the same keys, the
// same one-line messages (aggpack.ConfigError naming the key).

#include <pybind11/stl.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "aggpack/config/config.h"
#include "aggpack/core/error.h"
#include "bindings.h"

namespace aggpack::python {

namespace {

// A TOML basic string: quotes, backslashes and control characters escaped.
std::string toml_string(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\u%04x", static_cast<unsigned>(c));
      out += escaped;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

// A Python value as a TOML value: bool, int, float (shortest round-trip repr), str, list/tuple.
std::string toml_value(const py::handle& value, const std::string& key) {
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>() ? "true" : "false";
  if (py::isinstance<py::int_>(value)) return py::str(value).cast<std::string>();
  if (py::isinstance<py::float_>(value)) {
    const double number = value.cast<double>();
    if (std::isnan(number)) return "nan";
    if (std::isinf(number)) return number > 0 ? "inf" : "-inf";
    std::string text = py::repr(value).cast<std::string>();
    if (text.find_first_of(".eE") == std::string::npos) text += ".0";
    return text;
  }
  if (py::isinstance<py::str>(value)) return toml_string(value.cast<std::string>());
  if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
    std::string text = "[";
    for (const py::handle item : value) {
      text += (text.size() > 1 ? ", " : "") + toml_value(item, key);
    }
    return text + "]";
  }
  // numpy scalars and other numbers: by their float / int value.
  const auto object = py::reinterpret_borrow<py::object>(value);
  if (py::hasattr(object, "__index__")) return py::str(py::int_(object)).cast<std::string>();
  if (py::hasattr(object, "__float__")) return toml_value(py::float_(object), key);
  throw InvalidInput(key, py::repr(value).cast<std::string>(),
                     "a bool, int, float, str or list (a TOML value)");
}

// {"packer": {"kind": "random"}, "container.length": 1.0} -> one "dotted.key = value" line per
// leaf, in the dict's order.
void flatten(const py::dict& table, const std::string& prefix, std::string& text) {
  for (const auto& [k, v] : table) {
    if (!py::isinstance<py::str>(k)) {
      throw InvalidInput(prefix.empty() ? "config" : prefix, py::repr(k).cast<std::string>(),
                         "str keys (dotted config keys or table names)");
    }
    const std::string key = prefix + k.cast<std::string>();
    if (py::isinstance<py::dict>(v)) {
      flatten(v.cast<py::dict>(), key + ".", text);
    } else {
      text += key + " = " + toml_value(v, key) + "\n";
    }
  }
}

// Overrides as the CLI's --set strings: a list of "key=value" strings, or a dict key -> value.
std::vector<std::string> override_list(const py::object& overrides) {
  std::vector<std::string> list;
  if (overrides.is_none()) return list;
  if (py::isinstance<py::dict>(overrides)) {
    std::string text;
    flatten(overrides.cast<py::dict>(), "", text);
    std::size_t start = 0;
    while (start < text.size()) {
      const std::size_t end = text.find('\n', start);
      std::string line = text.substr(start, end - start);
      const std::size_t equals = line.find(" = ");
      list.push_back(line.substr(0, equals) + "=" + line.substr(equals + 3));
      start = end + 1;
    }
    return list;
  }
  return overrides.cast<std::vector<std::string>>();
}

std::string dict_to_toml(const py::dict& config) {
  std::string text;
  flatten(config, "", text);
  return text;
}

}  // namespace

PackConfig to_pack_config(const py::object& source) {
  if (py::isinstance<PackConfig>(source)) return source.cast<PackConfig>();
  if (py::isinstance<py::dict>(source)) {
    return parse_pack_config(dict_to_toml(source.cast<py::dict>()), "config dict", {});
  }
  const py::module_ os = py::module_::import("os");
  if (py::isinstance<py::str>(source) || py::isinstance(source, os.attr("PathLike"))) {
    return load_pack_config(os.attr("fspath")(source).cast<std::string>(), {});
  }
  throw InvalidInput("config", py::repr(source).cast<std::string>(),
                     "a PackConfig, a dict or the path of a TOML file (TOML text: pack_config())");
}

void register_config(py::module_& m) {
  py::class_<PackConfig>(m, "PackConfig", R"doc(A resolved, validated pack configuration: what
`aggpack pack CONFIG.toml --set ...` runs. Keys and defaults: docs/config.md (an empty
configuration is the paper's lattice case). Make one with pack_config(), PackConfig.from_toml,
PackConfig.from_file or PackConfig.from_dict; pass it to pack().)doc")
      .def_static(
          "from_toml",
          [](const std::string& text, const std::string& source_name, const py::object& overrides) {
            return parse_pack_config(text, source_name, override_list(overrides));
          },
          py::arg("text"), py::arg("source_name") = "config", py::arg("overrides") = py::none(),
          R"doc(Parses TOML text (as a config file holds), then applies `overrides` in order: a
list of "dotted.key=value" strings (the CLI's --set) or a dict {dotted key: value}. source_name
names the text in messages ("config:3: ..."). Raises FormatError (TOML syntax), ConfigError
(unknown key, wrong type, out of range; the message names the key), LimitExceeded.)doc")
      .def_static(
          "from_file",
          [](const std::string& path, const py::object& overrides) {
            return load_pack_config(path, override_list(overrides));
          },
          py::arg("path"), py::arg("overrides") = py::none(),
          "Reads a TOML file and parses it as from_toml (messages name the file). Raises IoError "
          "if it cannot be read.")
      .def_static(
          "from_dict",
          [](const py::dict& config, const py::object& overrides) {
            return parse_pack_config(dict_to_toml(config), "config dict", override_list(overrides));
          },
          py::arg("config"), py::arg("overrides") = py::none(),
          R"doc(The configuration a dict describes: nested tables ({"packer": {"kind": "random"}})
or dotted keys ({"packer.kind": "random"}), values bool, int, float, str or lists of them. It is
written as TOML, one key per line in the dict's order, and parsed as from_toml with source name
"config dict": messages read "config dict:LINE: ..." and name the key.)doc")
      .def_property_readonly(
          "resolved_toml", [](const PackConfig& c) { return c.resolved_toml; },
          "Every key at its effective value, as canonical TOML (what `aggpack pack "
          "--print-config` prints; stored in the native file's provenance).")
      .def_property_readonly(
          "warnings", [](const PackConfig& c) { return c.warnings; },
          "Keys given that have no effect with the chosen packer / container / grading, one "
          "sentence each (the CLI prints them as warnings).")
      .def_property_readonly("seed", &PackConfig::seed, "The chosen packer's seed.")
      .def_property_readonly("packer", &PackConfig::packer_name,
                             "The packer kind: 'lattice', 'random' or 'dense'.")
      .def_property_readonly(
          "threads", [](const PackConfig& c) { return c.threads; },
          "packer.threads: worker threads, 0 = all cores (results do not depend on it).")
      .def_property_readonly(
          "outputs", [](const PackConfig& c) { return c.outputs; },
          "The [output] table: format name -> path.")
      .def_property_readonly(
          "container", [](const PackConfig& c) { return container_dict(c.container()); },
          "The chosen packer's container as a dict (kind, sizes in m, wall_gap m, volume m^3).")
      .def("__repr__", [](const PackConfig& c) {
        return "<aggpack.PackConfig " + c.packer_name() + ", seed " + std::to_string(c.seed()) +
               ">";
      });

  m.def("_dict_to_toml", &dict_to_toml, py::arg("config"),
        "The TOML text PackConfig.from_dict parses for a dict (one dotted key per line).");

  m.def(
      "pack_config",
      [](const py::object& source, const py::object& overrides) {
        if (source.is_none()) return parse_pack_config("", "defaults", override_list(overrides));
        if (py::isinstance<py::dict>(source)) {
          return parse_pack_config(dict_to_toml(source.cast<py::dict>()), "config dict",
                                   override_list(overrides));
        }
        if (py::isinstance<py::str>(source)) {
          return parse_pack_config(source.cast<std::string>(), "config", override_list(overrides));
        }
        throw InvalidInput("config", py::repr(source).cast<std::string>(),
                           "None (the paper's case), a dict or a TOML string");
      },
      py::arg("config") = py::none(), py::arg("overrides") = py::none(),
      R"doc(A PackConfig from None (the paper's case: lattice, 1,050 particles in a 3.0 x 1.0 x
2.8 m box), a dict (PackConfig.from_dict) or TOML text (PackConfig.from_toml), then `overrides`
(a list of "key=value" strings or a dict). For a file use PackConfig.from_file(path).)doc");
}

}  // namespace aggpack::python
