#pragma once
// External readers that tests run on aggpack's outputs (installed by scripts/install-deps.sh), and
// the one rule for a missing one. A test starts with AGGPACK_REQUIRE_READER("gmsh"); when the
// reader is missing the test FAILS, naming the Debian package. Only AGGPACK_REQUIRE_READERS=0 (a
// developer machine without them) turns that into a skip; CI sets AGGPACK_REQUIRE_READERS=1, so
// there a missing reader can never pass as a skip (README, "Tests").

#include <gtest/gtest.h>

#include <array>
#include <cstdlib>
#include <map>
#include <string>
#include <string_view>

namespace aggpack::test {

/// One external reader: how to look for it, and the package that provides it.
struct ExternalReader {
  std::string_view name;  ///< the name tests pass to AGGPACK_REQUIRE_READER
  bool is_python_module;  ///< imported by /usr/bin/python3, else a program on the PATH
  std::string_view debian_package;
};

/// Every external reader any test uses.
inline constexpr std::array<ExternalReader, 7> kExternalReaders{{
    {.name = "admesh", .is_python_module = false, .debian_package = "admesh"},
    {.name = "ccx", .is_python_module = false, .debian_package = "calculix-ccx"},
    {.name = "gmsh", .is_python_module = false, .debian_package = "gmsh"},
    {.name = "yade", .is_python_module = false, .debian_package = "yade"},
    {.name = "meshio", .is_python_module = true, .debian_package = "python3-meshio"},
    {.name = "vtk", .is_python_module = true, .debian_package = "python3-vtk9"},
    {.name = "h5py", .is_python_module = true, .debian_package = "python3-h5py"},
}};

/// The reader called `name` (a test error, not a missing reader, when it is not listed above).
inline const ExternalReader* find_external_reader(std::string_view name) {
  for (const auto& reader : kExternalReaders) {
    if (reader.name == name) return &reader;
  }
  return nullptr;
}

/// True when the reader runs here (looked up once per test program; tests run on one thread).
inline bool is_reader_installed(const ExternalReader& reader) {
  static std::map<std::string, bool> known;
  const std::string name(reader.name);
  if (auto found = known.find(name); found != known.end()) return found->second;
  const std::string command =
      reader.is_python_module ? "cd / && /usr/bin/python3 -c 'import " + name + "' >/dev/null 2>&1"
                              : "command -v " + name + " >/dev/null 2>&1";
  return known[name] = std::system(command.c_str()) == 0;
}

/// False only when AGGPACK_REQUIRE_READERS=0: then a missing reader skips instead of failing.
inline bool are_readers_required() {
  const char* value = std::getenv("AGGPACK_REQUIRE_READERS");
  return value == nullptr || std::string_view(value) != "0";
}

/// "" when the reader is installed, else the message a test reports.
inline std::string missing_reader_message(std::string_view name) {
  const ExternalReader* reader = find_external_reader(name);
  if (reader == nullptr) {
    return "unknown external reader '" + std::string(name) +
           "' (list it in tests/support/readers.h)";
  }
  if (is_reader_installed(*reader)) return "";
  return std::string(reader->name) + " is not installed (Debian package " +
         std::string(reader->debian_package) + ", installed by scripts/install-deps.sh)";
}

}  // namespace aggpack::test

/// Use at the top of a test (or a void helper): continues when `reader` is installed, else FAILS
/// the test, or skips it when AGGPACK_REQUIRE_READERS=0.
#define AGGPACK_REQUIRE_READER(reader)                                                     \
  if (const std::string aggpack_missing = ::aggpack::test::missing_reader_message(reader); \
      aggpack_missing.empty()) {                                                           \
  } else if (::aggpack::test::are_readers_required() ||                                    \
             aggpack_missing.rfind("unknown", 0) == 0) {                                   \
    FAIL() << aggpack_missing << " [AGGPACK_REQUIRE_READERS=0 skips instead]";             \
  } else                                                                                   \
    GTEST_SKIP() << aggpack_missing << " [skipped: AGGPACK_REQUIRE_READERS=0]"
