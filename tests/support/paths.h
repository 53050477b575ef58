#pragma once
// Where the tests find the source tree and the aggpack program. The paths are compiled into
// tests/support/paths.cpp alone (tests/CMakeLists.txt), not into every test file, so a test
// object does not depend on where the tree is checked out and ccache reuses it across clones.

#include <string>

namespace aggpack::test {

/// The source tree's root, absolute, without a trailing slash.
const std::string& source_dir();

/// tests/io/fixtures/bad-inputs/ (inputs that broke earlier versions), with a trailing slash.
inline std::string bad_inputs_dir() { return source_dir() + "/tests/io/fixtures/bad-inputs/"; }

/// The built `aggpack` program's absolute path.
const std::string& aggpack_binary();

}  // namespace aggpack::test
