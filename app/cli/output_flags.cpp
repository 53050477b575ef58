#include "output_flags.h"

#include <sys/stat.h>

#include <charconv>
#include <system_error>

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

std::uint64_t parse_seed_flag(std::string_view flag, const std::string& text) {
  constexpr std::uint64_t kLargestSeed = 9223372036854775807ULL;  // 2^63 - 1
  std::uint64_t seed = 0;
  const char* end = text.data() + text.size();
  const auto [last, status] = std::from_chars(text.data(), end, seed);  // no sign allowed
  if (text.empty() || status != std::errc() || last != end || seed > kLargestSeed) {
    throw InvalidInput(std::string(flag), text.empty() ? "\"\"" : clipped(text, 40),
                       "an integer in [0, 2^63 - 1]");
  }
  return seed;
}

}  // namespace aggpack::cli
