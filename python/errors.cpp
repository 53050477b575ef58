// Library errors as Python exceptions (aggpack/core/error.h, aggpack/config/schema.h): one class
// per C++ class, the same one-line message.
//   aggpack.Error                      base (attribute `kind`: "invalid input", ...)
//     aggpack.InvalidInput(ValueError) attribute `field`: the key, argument or field at fault
//       aggpack.ConfigError            attribute `key`: the dotted config key ("" for syntax)
//     aggpack.IoError(OSError)
//     aggpack.FormatError(ValueError)
//     aggpack.LimitExceeded
// A C++ Error of another class is raised as the class of its kind.

#include <Python.h>

#include <exception>
#include <string>

#include "aggpack/config/schema.h"
#include "aggpack/core/error.h"
#include "bindings.h"

namespace aggpack::python {

namespace {

struct Classes {
  py::handle base, invalid_input, config_error, io_error, format_error, limit_exceeded;
};

Classes& classes() {
  static Classes instance;
  return instance;
}

const char* kind_text(ErrorKind kind) {
  switch (kind) {
    case ErrorKind::kInvalidInput:
      return "invalid input";
    case ErrorKind::kIoError:
      return "io error";
    case ErrorKind::kFormatError:
      return "format error";
    case ErrorKind::kLimitExceeded:
      return "limit exceeded";
  }
  return "error";
}

py::handle class_of(ErrorKind kind) {
  const Classes& c = classes();
  switch (kind) {
    case ErrorKind::kInvalidInput:
      return c.invalid_input;
    case ErrorKind::kIoError:
      return c.io_error;
    case ErrorKind::kFormatError:
      return c.format_error;
    case ErrorKind::kLimitExceeded:
      return c.limit_exceeded;
  }
  return c.base;
}

// Raises `type(message)` with the attributes kind (and field or key when given).
void raise(py::handle type, const Error& error, const char* attribute, const std::string& value) {
  // The CLI's advice in Python's words: the keyword is force=True, not the flag --force.
  std::string message = error.what();
  const std::string flag_advice = "(use --force to replace it)";
  if (const auto at = message.find(flag_advice); at != std::string::npos) {
    message.replace(at, flag_advice.size(), "(pass force=True to replace it)");
  }
  py::object instance = type(py::str(message));
  instance.attr("kind") = kind_text(error.kind());
  if (attribute != nullptr) instance.attr(attribute) = value;
  PyErr_SetObject(type.ptr(), instance.ptr());
}

py::handle make_class(py::module_& m, const char* name, py::tuple bases, const char* doc) {
  const std::string qualified = std::string("aggpack.") + name;
  PyObject* type = PyErr_NewExceptionWithDoc(qualified.c_str(), doc, bases.ptr(), nullptr);
  if (type == nullptr) throw py::error_already_set();
  m.add_object(name, py::handle(type));  // the module holds the reference from here on
  return type;
}

}  // namespace

void register_errors(py::module_& m) {
  Classes& c = classes();
  const py::handle exception(PyExc_Exception);
  const py::handle value_error(PyExc_ValueError);
  const py::handle os_error(PyExc_OSError);
  c.base = make_class(m, "Error", py::make_tuple(exception),
                      "Base of every aggpack error. Attribute kind: 'invalid input', 'io error', "
                      "'format error' or 'limit exceeded'. The message is one line.");
  c.invalid_input =
      make_class(m, "InvalidInput", py::make_tuple(c.base, value_error),
                 "A parameter or configuration value outside its allowed range; the message "
                 "names it, its value and what is allowed. Attribute field: the name at fault.");
  c.config_error = make_class(
      m, "ConfigError", py::make_tuple(c.invalid_input),
      "A configuration that cannot be used (unknown key, wrong type, out of range, bad word), as "
      "`aggpack pack` reports it. Attribute key: the dotted key ('' for a TOML syntax error).");
  c.io_error = make_class(m, "IoError", py::make_tuple(c.base, os_error),
                          "A file that cannot be opened, created, written or renamed.");
  c.format_error =
      make_class(m, "FormatError", py::make_tuple(c.base, value_error),
                 "A file (or TOML text) that was read but whose content is wrong: syntax, "
                 "truncation, corruption, another format version.");
  c.limit_exceeded = make_class(
      m, "LimitExceeded", py::make_tuple(c.base),
      "A computation that would exceed a set cap (vertex cap, attempt budget, step count).");

  py::register_exception_translator([](std::exception_ptr pointer) {
    if (!pointer) return;
    const Classes& k = classes();
    try {
      std::rethrow_exception(pointer);
    } catch (const ConfigError& error) {
      raise(k.config_error, error, "key", error.key());
      // InvalidInput's field is the key too, so `except aggpack.InvalidInput as e: e.field` works.
      PyObject* type = nullptr;
      PyObject* value = nullptr;
      PyObject* trace = nullptr;
      PyErr_Fetch(&type, &value, &trace);
      if (value != nullptr) PyObject_SetAttrString(value, "field", py::str(error.key()).ptr());
      PyErr_Restore(type, value, trace);
    } catch (const InvalidInput& error) {
      raise(k.invalid_input, error, "field", error.field());
    } catch (const Error& error) {
      raise(class_of(error.kind()), error, nullptr, "");
    }
  });
}

}  // namespace aggpack::python
