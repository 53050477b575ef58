#include "aggpack/core/atomic_file.h"

#include <fcntl.h>
#include <limits.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>

#include "aggpack/core/error.h"
#include "aggpack/core/temp_paths.h"
#include "aggpack/core/text.h"

namespace aggpack {

namespace fs = std::filesystem;

namespace {

const char* kind_of(mode_t mode) {
  if (S_ISDIR(mode)) return "directory";
  if (S_ISCHR(mode)) return "character device";
  if (S_ISBLK(mode)) return "block device";
  if (S_ISFIFO(mode)) return "FIFO";
  if (S_ISSOCK(mode)) return "socket";
  if (S_ISLNK(mode)) return "symbolic link";
  return "special file";
}

std::string folder_of(const std::string& path) {
  std::string folder = fs::path(path).parent_path().string();
  return folder.empty() ? std::string(".") : folder;
}

// Creates "<folder>/.aggpack.tmp.XXXXXX" and registers it for removal on a signal.
int create_temporary(const std::string& folder, std::string& created, int& slot) {
  const std::string pattern = temporary_pattern(folder);
  std::vector<char> buffer(pattern.begin(), pattern.end());
  buffer.push_back('\0');
  const CleanupSignalBlock block;
  const int descriptor = ::mkostemp(buffer.data(), O_CLOEXEC);
  if (descriptor >= 0) {
    created = buffer.data();
    slot = register_temporary(created);
  }
  return descriptor;
}

}  // namespace

Wording write_failure_wording(const std::string& path, int error) {
  switch (error) {
    case ENOSPC:
      return {Sentence::kWriteDiskFull, {path}};
    case EDQUOT:
      return {Sentence::kWriteQuota, {path}};
    case EFBIG:
      return {Sentence::kWriteTooLarge, {path}};
    case 0:
      return {Sentence::kWriteError, {path}};
    default:
      return {Sentence::kWriteSystemError, {path, std::strerror(error)}};
  }
}

// ---- OutputStream ------------------------------------------------------------------------------

OutputStream::Buffer::Buffer() : storage_(std::size_t{1} << 16) {
  setp(storage_.data(), storage_.data() + storage_.size());
}

bool OutputStream::Buffer::drain() {
  const char* data = pbase();
  std::size_t left = static_cast<std::size_t>(pptr() - pbase());
  setp(storage_.data(), storage_.data() + storage_.size());
  if (error != 0) return false;
  if (descriptor < 0) {
    if (left > 0) error = EBADF;
    return left == 0;
  }
  while (left > 0) {
    const ssize_t written = ::write(descriptor, data, left);
    if (written < 0) {
      if (errno == EINTR) continue;
      error = errno;
      return false;
    }
    data += written;
    left -= static_cast<std::size_t>(written);
  }
  return true;
}

OutputStream::Buffer::int_type OutputStream::Buffer::overflow(int_type c) {
  if (!drain()) return traits_type::eof();
  if (!traits_type::eq_int_type(c, traits_type::eof())) {
    *pptr() = traits_type::to_char_type(c);
    pbump(1);
  }
  return traits_type::not_eof(c);
}

int OutputStream::Buffer::sync() { return drain() ? 0 : -1; }

OutputStream::OutputStream() : std::ostream(nullptr) { rdbuf(&buffer_); }

OutputStream::~OutputStream() { close(); }

void OutputStream::attach(int descriptor) {
  buffer_.descriptor = descriptor;
  buffer_.error = 0;
  clear();
}

bool OutputStream::close() {
  if (buffer_.descriptor < 0) return buffer_.error == 0;
  const bool is_drained = buffer_.drain();
  if (::close(buffer_.descriptor) != 0 && buffer_.error == 0) buffer_.error = errno;
  buffer_.descriptor = -1;
  if (!is_drained || buffer_.error != 0) setstate(std::ios::badbit);
  return buffer_.error == 0;
}

bool OutputStream::is_open() const { return buffer_.descriptor >= 0; }

int OutputStream::error() const { return buffer_.error; }

namespace {

// "cannot write <path>: file name too long (300 bytes, at most 255)": the longest name of the path
// against NAME_MAX, else the whole path against PATH_MAX. The path is clipped: it is long.
Wording name_too_long_wording(const std::string& path) {
  std::size_t longest = 0;
  for (const auto& part : fs::path(path)) longest = std::max(longest, part.native().size());
  if (longest > NAME_MAX) {
    return {Sentence::kWriteNameTooLong,
            {clipped(path, 80), std::to_string(longest), std::to_string(NAME_MAX)}};
  }
  return {Sentence::kWritePathTooLong,
          {clipped(path, 80), std::to_string(path.size()), std::to_string(PATH_MAX)}};
}

}  // namespace

// ---- what may be replaced ----------------------------------------------------------------------

std::string output_destination(const std::string& path, Overwrite overwrite) {
  if (path.empty()) throw IoError(Wording{Sentence::kOutputPathEmpty, {}});
  struct stat link_status {};
  if (::lstat(path.c_str(), &link_status) != 0) {
    if (errno == ENAMETOOLONG) throw IoError(name_too_long_wording(path));
    return path;  // absent (or its folder is missing: check_writable says so)
  }
  const auto exists = [&] {
    return IoError(Wording{Sentence::kWriteFileExists, {path, "--force"}});
  };
  if (S_ISREG(link_status.st_mode)) {
    if (overwrite == Overwrite::kForbid) throw exists();
    return path;
  }
  if (!S_ISLNK(link_status.st_mode)) {
    throw IoError(Wording{Sentence::kReplaceNotRegular, {path, kind_of(link_status.st_mode)}});
  }
  struct stat target_status {};
  if (::stat(path.c_str(), &target_status) != 0) {
    throw IoError(Wording{Sentence::kReplaceMissingLink, {path}});
  }
  if (!S_ISREG(target_status.st_mode)) {
    throw IoError(
        Wording{Sentence::kReplaceLinkNotRegular, {path, kind_of(target_status.st_mode)}});
  }
  if (overwrite == Overwrite::kForbid) throw exists();
  std::unique_ptr<char, decltype(&std::free)> resolved(::realpath(path.c_str(), nullptr),
                                                       &std::free);
  if (!resolved) {
    throw IoError(Wording{Sentence::kResolveLink, {path, std::strerror(errno)}});
  }
  return resolved.get();
}

void check_writable(const std::string& path, Overwrite overwrite) {
  if (path.empty()) throw IoError(Wording{Sentence::kOutputPathEmpty, {}});
  check_folder_writable(folder_of(output_destination(path, overwrite)), path);
}

namespace {

void check_folder(const std::string& folder, const std::string& path) {
  std::error_code error;
  if (!fs::is_directory(folder, error)) {
    throw IoError(Wording{Sentence::kWriteNoFolder, {path, folder}});
  }
  if (::access(folder.c_str(), W_OK) != 0) {
    throw IoError(Wording{Sentence::kWriteNoPermission, {path, folder}});
  }
}

}  // namespace

void check_folder_writable(const std::string& folder_path, const std::string& path) {
  const std::string folder = folder_path.empty() ? std::string(".") : folder_path;
  check_folder(folder, path);
  // access() says yes to root everywhere (e.g. /proc): really create a file.
  std::string probe;
  int slot = -1;
  const int descriptor = create_temporary(folder, probe, slot);
  if (descriptor < 0) {
    throw IoError(Wording{Sentence::kWriteCannotCreate, {path, folder, std::strerror(errno)}});
  }
  ::close(descriptor);
  ::unlink(probe.c_str());
  unregister_temporary(slot);
}

// ---- AtomicFile --------------------------------------------------------------------------------

AtomicFile::AtomicFile(std::string path, Overwrite overwrite, std::ios::openmode /*mode*/)
    : path_(std::move(path)), overwrite_(overwrite) {
  // No probe file: creating the temporary is the real test.
  destination_ = output_destination(path_, overwrite);
  check_folder(folder_of(destination_), path_);
  const int descriptor = create_temporary(folder_of(destination_), temporary_path_, slot_);
  if (descriptor < 0) {
    throw IoError(Wording{Sentence::kWriteCannotCreateTemporary,
                          {path_, folder_of(destination_), std::strerror(errno)}});
  }
  stream_.attach(descriptor);
}

AtomicFile::~AtomicFile() {
  if (!is_committed_) {
    stream_.close();
    if (!temporary_path_.empty()) ::unlink(temporary_path_.c_str());
    unregister_temporary(slot_);
  }
}

Wording AtomicFile::write_error_wording() const {
  return write_failure_wording(path_, stream_.error());
}

void AtomicFile::commit() {
  if (stream_.is_open()) {
    stream_.flush();
    if (!stream_.close() || !stream_.good()) throw IoError(write_error_wording());
  }
  // Files get the usual permissions (mkstemp makes them 0600), less the umask.
  const mode_t mask = ::umask(0);
  ::umask(mask);
  ::chmod(temporary_path_.c_str(), 0666 & ~mask);
  // The destination may have changed type since the constructor (a long run): check again.
  if (output_destination(path_, overwrite_) != destination_) {
    throw IoError(Wording{Sentence::kWriteChanged, {path_}});
  }
  if (std::rename(temporary_path_.c_str(), destination_.c_str()) != 0) {
    throw IoError(
        Wording{Sentence::kRenameFailed, {temporary_path_, destination_, std::strerror(errno)}});
  }
  is_committed_ = true;
  unregister_temporary(slot_);
}

// ---- OutputTransaction -------------------------------------------------------------------------

void OutputTransaction::add(const std::string& path) {
  Entry entry;
  entry.destination = output_destination(path, Overwrite::kAllow);
  struct stat status {};
  entry.existed = ::lstat(entry.destination.c_str(), &status) == 0;
  if (entry.existed) {
    // A hard link keeps the old content whatever happens to the name.
    std::string reserved;
    int slot = -1;
    const int descriptor = create_temporary(folder_of(entry.destination), reserved, slot);
    if (descriptor >= 0) {
      ::close(descriptor);
      ::unlink(reserved.c_str());
      if (::link(entry.destination.c_str(), reserved.c_str()) == 0) {
        entry.backup = reserved;
        entry.slot = slot;
      } else {
        unregister_temporary(slot);
      }
    }
  }
  entries_.push_back(std::move(entry));
}

void OutputTransaction::commit() {
  for (Entry& entry : entries_) {
    if (!entry.backup.empty()) ::unlink(entry.backup.c_str());
    unregister_temporary(entry.slot);
  }
  is_committed_ = true;
}

OutputTransaction::~OutputTransaction() {
  if (is_committed_) return;
  for (Entry& entry : entries_) {
    if (!entry.backup.empty()) {
      // rename() between two links of one file does nothing: then the file was never replaced.
      struct stat backup {};
      struct stat current {};
      const bool is_same = ::stat(entry.backup.c_str(), &backup) == 0 &&
                           ::stat(entry.destination.c_str(), &current) == 0 &&
                           backup.st_dev == current.st_dev && backup.st_ino == current.st_ino;
      if (is_same) {
        ::unlink(entry.backup.c_str());
      } else {
        ::rename(entry.backup.c_str(), entry.destination.c_str());
      }
    } else if (!entry.existed) {
      ::unlink(entry.destination.c_str());
    }
    unregister_temporary(entry.slot);
  }
}

}  // namespace aggpack
