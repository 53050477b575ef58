#include "aggpack/core/atomic_file.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <vector>

#include "aggpack/core/error.h"

namespace aggpack {

namespace fs = std::filesystem;

void check_writable(const std::string& path, Overwrite overwrite) {
  if (path.empty()) throw IoError("output path is empty");
  const fs::path target(path);
  fs::path folder = target.parent_path();
  if (folder.empty()) folder = ".";
  std::error_code error;
  if (!fs::is_directory(folder, error)) {
    throw IoError("cannot write " + path + ": folder " + folder.string() + " does not exist");
  }
  if (::access(folder.c_str(), W_OK) != 0) {
    throw IoError("cannot write " + path + ": no permission to write in folder " + folder.string());
  }
  if (fs::is_directory(target, error)) {
    throw IoError("cannot write " + path + ": it is a folder");
  }
  if (overwrite == Overwrite::kForbid && fs::exists(target, error)) {
    throw IoError("cannot write " + path + ": file exists (use --force to replace it)");
  }
}

AtomicFile::AtomicFile(std::string path, Overwrite overwrite, std::ios::openmode mode)
    : path_(std::move(path)) {
  check_writable(path_, overwrite);
  std::string pattern = path_ + ".tmp.XXXXXX";
  std::vector<char> buffer(pattern.begin(), pattern.end());
  buffer.push_back('\0');
  const int descriptor = ::mkstemp(buffer.data());
  if (descriptor < 0) {
    throw IoError("cannot create a temporary file for " + path_ + ": " + std::strerror(errno));
  }
  ::close(descriptor);
  temporary_path_ = buffer.data();
  stream_.open(temporary_path_, mode | std::ios::out | std::ios::trunc);
  if (!stream_) {
    std::remove(temporary_path_.c_str());
    throw IoError("cannot open " + temporary_path_ + " for writing");
  }
}

AtomicFile::~AtomicFile() {
  if (!is_committed_) {
    stream_.close();
    std::remove(temporary_path_.c_str());
  }
}

void AtomicFile::commit() {
  if (stream_.is_open()) {
    stream_.flush();
    const bool is_good = stream_.good();
    stream_.close();
    if (!is_good) throw IoError("write error on " + path_ + " (disk full?)");
  }
  // Files get the usual permissions (mkstemp makes them 0600).
  std::error_code error;
  fs::permissions(temporary_path_,
                  fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read |
                      fs::perms::others_read,
                  error);
  if (std::rename(temporary_path_.c_str(), path_.c_str()) != 0) {
    throw IoError("cannot rename " + temporary_path_ + " to " + path_ + ": " +
                  std::strerror(errno));
  }
  is_committed_ = true;
}

}  // namespace aggpack
