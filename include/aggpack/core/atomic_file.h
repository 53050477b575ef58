#pragma once
// Atomic output files: write to a temporary file in the destination folder, then rename over the
// destination on commit(). If commit() is never reached (an exception, a crash) the destination
// is untouched and the temporary file is removed by the destructor.

#include <fstream>
#include <string>

namespace aggpack {

/// Whether an existing destination may be replaced.
enum class Overwrite { kAllow, kForbid };

class AtomicFile {
 public:
  /// Opens a temporary file beside `path`. \throw IoError if the folder does not exist or is not
  /// writable, or (with Overwrite::kForbid) if `path` exists.
  explicit AtomicFile(std::string path, Overwrite overwrite = Overwrite::kAllow,
                      std::ios::openmode mode = std::ios::out | std::ios::binary);
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  ~AtomicFile();

  /// The stream to write to.
  std::ofstream& stream() { return stream_; }
  /// The temporary path (for libraries that open files by name, e.g. HDF5: close stream first).
  [[nodiscard]] const std::string& temporary_path() const { return temporary_path_; }
  /// Flushes, checks for write errors, and renames onto the destination. \throw IoError
  void commit();

 private:
  std::string path_;
  std::string temporary_path_;
  std::ofstream stream_;
  bool is_committed_ = false;
};

/// Checks up front that `path` can be created: its folder exists and is writable, and (with
/// Overwrite::kForbid) it does not exist yet. \throw IoError naming the path and the reason.
void check_writable(const std::string& path, Overwrite overwrite);

}  // namespace aggpack
