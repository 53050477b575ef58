#pragma once
// Atomic output files: write to a temporary file in the destination folder, then rename over the
// destination on commit(). If commit() is never reached (an exception, a crash) the destination
// is untouched and the temporary file is removed by the destructor; on SIGINT, SIGTERM or SIGHUP
// it is removed by the handler of temp_paths.h.
//
// What may be replaced (README "Errors"): only a regular file. A device node, FIFO, socket or
// folder is refused with "refusing to replace <path>: not a regular file (<kind>)", with or
// without --force. A symbolic link to a regular file is followed: the file it points to is
// replaced (atomically, in that file's folder) and the link stays; a link to anything else, or a
// dangling link, is refused.

#include <ios>
#include <ostream>
#include <streambuf>
#include <string>
#include <vector>

#include "aggpack/core/error_words.h"

namespace aggpack {

/// Whether an existing destination may be replaced.
enum class Overwrite { kAllow, kForbid };

/// An output stream on a file descriptor that remembers the errno of the first failed write, so
/// that "disk full" can be told apart from other failures.
class OutputStream : public std::ostream {
 public:
  OutputStream();
  OutputStream(const OutputStream&) = delete;
  OutputStream& operator=(const OutputStream&) = delete;
  ~OutputStream() override;
  /// Takes ownership of an open descriptor.
  void attach(int descriptor);
  /// Flushes and closes; false (and the stream bad) if a write or the close failed.
  bool close();
  [[nodiscard]] bool is_open() const;
  /// errno of the first failure, 0 if none.
  [[nodiscard]] int error() const;

 private:
  class Buffer : public std::streambuf {
   public:
    Buffer();
    int descriptor = -1;
    int error = 0;
    bool drain();

   protected:
    int_type overflow(int_type c) override;
    int sync() override;

   private:
    std::vector<char> storage_;
  };
  Buffer buffer_;
};

class AtomicFile {
 public:
  /// Opens a temporary file beside `path` (beside the file a symbolic link points to).
  /// \throw IoError if the folder does not exist or is not writable, if `path` is not a regular
  /// file, or (with Overwrite::kForbid) if `path` exists. `mode` is accepted for compatibility:
  /// output is always binary.
  explicit AtomicFile(std::string path, Overwrite overwrite = Overwrite::kAllow,
                      std::ios::openmode mode = std::ios::out | std::ios::binary);
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  ~AtomicFile();

  /// The stream to write to.
  OutputStream& stream() { return stream_; }
  /// The temporary path (for libraries that open files by name, e.g. HDF5: close stream first).
  [[nodiscard]] const std::string& temporary_path() const { return temporary_path_; }
  /// "cannot write <path>: disk full" (or the reason of the stream's first failed write).
  [[nodiscard]] Wording write_error_wording() const;
  /// Flushes, checks for write errors, and renames onto the destination. \throw IoError
  void commit();

 private:
  std::string path_;         // as given (for messages)
  std::string destination_;  // what is replaced: path_, or the file a link points to
  std::string temporary_path_;
  Overwrite overwrite_;
  OutputStream stream_;
  int slot_ = -1;  // temp_paths registration
  bool is_committed_ = false;
};

/// Checks up front that `path` can be created: it is absent or a regular file (see the policy
/// above; with Overwrite::kForbid it must be absent), its folder exists, and a file can really be
/// created there (a probe file is created and removed). \throw IoError naming the path and the
/// reason.
void check_writable(const std::string& path, Overwrite overwrite);

/// Checks that a file can be created in `folder` (exists, writable, a probe file really created
/// and removed); messages name `path`, the output that will go there. \throw IoError
void check_folder_writable(const std::string& folder, const std::string& path);

/// The file that writing `path` replaces: `path` itself, or the regular file a symbolic link
/// points to. \throw IoError for anything but an absent path or a regular file (and, with
/// Overwrite::kForbid, for an existing one).
std::string output_destination(const std::string& path, Overwrite overwrite);

/// "cannot write <path>: disk full" / "...: disk quota exceeded" / "...: file too large (file
/// size limit)" / "...: <strerror>", in its sentence (error_words.h).
Wording write_failure_wording(const std::string& path, int error);

/// A command's outputs, all or nothing: add() every output before writing it; unless commit() is
/// called, the destructor removes each output this run created and puts back each file it
/// replaced (kept as a hard link beside it; where the file system has no hard links the replaced
/// file cannot be restored and the new one is kept).
class OutputTransaction {
 public:
  OutputTransaction() = default;
  OutputTransaction(const OutputTransaction&) = delete;
  OutputTransaction& operator=(const OutputTransaction&) = delete;
  ~OutputTransaction();
  /// Records `path` (call after check_writable, before writing).
  void add(const std::string& path);
  /// Keeps the outputs and removes the backups.
  void commit();

 private:
  struct Entry {
    std::string destination;
    std::string backup;  // empty: nothing to restore
    bool existed = false;
    int slot = -1;
  };
  std::vector<Entry> entries_;
  bool is_committed_ = false;
};

}  // namespace aggpack
