#pragma once
// Whole files as bytes for tests: read, write, and compare two of them without GoogleTest's
// line diff.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace aggpack::test {

/// A whole file as bytes ("" when it cannot be read).
inline std::string file_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// Writes `bytes` as the whole file (replacing it).
inline void write_file(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

/// Whether two files' bytes are the same; on a difference, the first differing line (number and
/// both texts, cut to 200 characters) and the sizes. Use it instead of EXPECT_EQ on file contents:
/// GoogleTest's diff of two long multi-line strings builds a line-by-line edit table (lines x
/// lines cells), which for two 3 MB meshes took 24 GB and the OOM killer ended the test program.
inline ::testing::AssertionResult same_bytes(const std::string& a, const std::string& b) {
  if (a == b) return ::testing::AssertionSuccess();
  const std::size_t offset = static_cast<std::size_t>(
      std::mismatch(a.begin(), a.end(), b.begin(), b.end()).first - a.begin());
  const std::size_t line_start = a.rfind('\n', offset == 0 ? 0 : offset - 1);
  const std::size_t begin = line_start == std::string::npos || offset == 0 ? 0 : line_start + 1;
  const auto line_of = [begin](const std::string& text) {
    if (begin >= text.size()) return std::string("<end of file>");
    const std::size_t end = text.find('\n', begin);
    return text.substr(
        begin, std::min<std::size_t>(200, (end == std::string::npos ? text.size() : end) - begin));
  };
  return ::testing::AssertionFailure()
         << "the bytes differ (sizes " << a.size() << " and " << b.size() << ") from line "
         << 1 + std::count(a.begin(), a.begin() + static_cast<std::ptrdiff_t>(begin), '\n')
         << ":\n  " << line_of(a) << "\n  " << line_of(b);
}

}  // namespace aggpack::test
