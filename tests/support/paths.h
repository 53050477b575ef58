#pragma once
// Where the tests find the source tree and the aggpack program. The paths are compiled into
// tests/support/paths.cpp alone (tests/CMakeLists.txt), not into every test file, so a test
// object does not depend on where the tree is checked out and ccache reuses it across clones.

#include <string>

namespace aggpack::test {

/// The source tree's root, absolute, without a trailing slash.
const std::string& source_dir();

/// The built `aggpack` program's absolute path.
const std::string& aggpack_binary();

}  // namespace aggpack::test
