#include "output_flags.h"

#include <sys/stat.h>

#include "aggpack/core/error.h"
#include "aggpack/core/text.h"

namespace aggpack::cli {

void check_output_file_flag(std::string_view flag, const std::string& path) {
  if (path.empty()) throw InvalidInput(std::string(flag), "\"\"", "a file path");
  // An existing folder gets the message of every other output that is not a regular file
  // (core/atomic_file.h); a name ending in '/' can only be a folder.
  struct stat status {};
  if (::stat(path.c_str(), &status) == 0 && S_ISDIR(status.st_mode)) {
    throw IoError("refusing to replace " + clipped(path) + ": not a regular file (directory)");
  }
  if (path.back() == '/') {
    throw IoError("cannot write " + clipped(path) + ": a folder name (ends in '/'); " +
                  std::string(flag) + " takes a file path");
  }
}

void check_output_folder_flag(std::string_view flag, const std::string& path) {
  if (path.empty()) throw InvalidInput(std::string(flag), "\"\"", "a folder path");
  struct stat status {};
  if (::stat(path.c_str(), &status) == 0 && !S_ISDIR(status.st_mode)) {
    throw IoError("cannot write " + clipped(path) + ": not a folder; " + std::string(flag) +
                  " takes a folder path");
  }
}

}  // namespace aggpack::cli
