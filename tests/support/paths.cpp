#include "support/paths.h"

namespace aggpack::test {

const std::string& source_dir() {
  static const std::string path = AGGPACK_SOURCE_DIR;
  return path;
}

const std::string& aggpack_binary() {
  static const std::string path = AGGPACK_BINARY;
  return path;
}

}  // namespace aggpack::test
