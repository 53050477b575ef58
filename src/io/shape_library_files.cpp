// Loading a shape library: list the folder, then read, hash and import each file in parallel.

#include "aggpack/io/shape_library_files.h"

#include <algorithm>
#include <cerrno>
#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "aggpack/core/error.h"
#include "aggpack/core/parallel.h"
#include "aggpack/core/text.h"
#include "aggpack/io/mesh_read.h"
#include "read_failure.h"

namespace aggpack {

namespace {

constexpr std::size_t kMaxFiles = 1000000;

using FileList = std::vector<std::pair<std::string, std::string>>;

// The files one library path names: (full path, name) in name order.
FileList list_files(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code error;
  const auto status = fs::status(path, error);
  // Behind a folder the user may not enter: say so, not "no such file or folder".
  if (error && error.value() == EACCES) {
    throw IoError(io_detail::read_failure_wording(path, EACCES));
  }
  std::vector<std::pair<std::string, std::string>> files;
  MeshFileFormat format{};
  if (!error && fs::is_directory(status)) {
    for (fs::directory_iterator it(path, error), end; !error && it != end; it.increment(error)) {
      const auto& entry = *it;
      std::error_code entry_error;
      if (!entry.is_regular_file(entry_error)) continue;
      const std::string name = entry.path().filename().string();
      if (!mesh_file_format(name, format)) continue;
      if (files.size() >= kMaxFiles) {
        throw LimitExceeded("particle.library", aggpack::quoted(path),
                            Wording{Sentence::kLibraryTooManyFiles, {}});
      }
      files.emplace_back(entry.path().string(), name);
    }
    if (error) throw IoError(Wording{Sentence::kLibraryList, {path, error.message()}});
    if (files.empty()) {
      throw InvalidInput("particle.library", aggpack::quoted(path),
                         Wording{Sentence::kLibraryFolderEmpty, {}});
    }
  } else if (!error && fs::is_regular_file(status)) {
    if (!mesh_file_format(path, format)) {
      throw InvalidInput("particle.library", aggpack::quoted(path),
                         Wording{Sentence::kLibraryFileExtension, {}});
    }
    files.emplace_back(path, fs::path(path).filename().string());
  } else {
    throw InvalidInput("particle.library", aggpack::quoted(path),
                       Wording{Sentence::kLibraryPathMissing, {}});
  }
  std::sort(files.begin(), files.end(),
            [](const auto& a, const auto& b) { return a.second < b.second; });
  return files;
}

// The files of every library path, in the paths' order. With several paths a shape is named by
// its path (two folders may both hold "a.stl"); a file named twice is refused.
FileList list_all_files(const std::vector<std::string>& paths) {
  if (paths.size() == 1) return list_files(paths.front());
  namespace fs = std::filesystem;
  FileList all;
  std::set<fs::path> seen;
  for (const std::string& path : paths) {
    if (path.empty()) {
      throw InvalidInput("particle.library", "\"\"", Wording{Sentence::kLibraryPathEmpty, {}});
    }
    for (auto& [full, name] : list_files(path)) {
      std::error_code error;
      fs::path canonical = fs::weakly_canonical(full, error);
      if (error) canonical = fs::path(full).lexically_normal();
      if (!seen.insert(canonical).second) {
        throw InvalidInput("particle.library", aggpack::quoted(path),
                           Wording{Sentence::kLibraryNamedTwice, {full}});
      }
      if (all.size() >= kMaxFiles) {
        throw LimitExceeded("particle.library", aggpack::quoted(path),
                            Wording{Sentence::kLibraryTooManyFiles, {}});
      }
      all.emplace_back(full, full);
    }
  }
  return all;
}

struct Outcome {
  std::optional<LibraryShape> shape;
  ErrorKind kind = ErrorKind::kFormatError;
  std::string message;              // without the file name
  Wording wording;                  // the whole message (the file name first)
  std::vector<WordedValue> worded;  // its values that are sentences of their own
};

Outcome import_file(const std::string& path, const std::string& name,
                    const ShapeImportOptions& options) {
  Outcome outcome;
  try {
    const std::string content = read_file_bytes(path, kMaxMeshFileBytes);
    MeshFileFormat format{};
    mesh_file_format(name, format);
    std::string hash = content_hash(content);
    const TriangleMesh mesh = parse_mesh(content, format, path);
    outcome.shape = import_shape(mesh, options, name, std::move(hash), path);
  } catch (const Error& error) {
    outcome.kind = error.kind();
    std::string message = error.what();
    // Reader messages start with the path already; the others get it below.
    if (message.rfind(path, 0) == 0) message = message.substr(path.size());
    if (message.rfind(": ", 0) == 0 || message.rfind(":", 0) == 0) {
      message = message.substr(message[1] == ' ' ? 2 : 1);
    }
    outcome.message = message;
    // A reader's sentence names the file first (its message starts with it); any other message
    // follows the file name. A file over the size cap names its size and the cap.
    const Wording& field = error.field_wording();
    const Wording& size = error.value_wording();
    if (error.has_value() && field.sentence == Sentence::kFileSize &&
        size.sentence == Sentence::kBytes && error.wording().sentence == Sentence::kAtMostBytes &&
        !field.values.empty() && !size.values.empty() && !error.wording().values.empty()) {
      outcome.wording = {
          Sentence::kMeshFileSize,
          {path, field.values.front(), size.values.front(), error.wording().values.front()}};
    } else {
      const bool is_sentence = error.wording().sentence != Sentence::kText && !error.has_value();
      if (is_sentence && !error.wording().values.empty() &&
          error.wording().values.front() == path) {
        outcome.wording = error.wording();
      } else {
        outcome.wording = {Sentence::kMeshProblem, {path, message}};
        // A sentence that does not name the file ("mesh has no convex hull: ...") follows it.
        if (is_sentence && message == error.what()) outcome.worded = {{message, error.wording()}};
      }
      outcome.worded.insert(outcome.worded.end(), error.worded_values().begin(),
                            error.worded_values().end());
    }
  } catch (const std::bad_alloc&) {
    outcome.kind = ErrorKind::kLimitExceeded;
    outcome.message = "out of memory while reading it";
    outcome.wording = {Sentence::kMeshOutOfMemory, {path}};
  }
  return outcome;
}

}  // namespace

void check_library_paths(const ShapeLibraryOptions& options) {
  (void)list_all_files(options.paths);
}

ShapeLibrary load_shape_library(const ShapeLibraryOptions& options) {
  validate(options.import);
  if (options.paths.empty() || (options.paths.size() == 1 && options.paths.front().empty())) {
    throw InvalidInput("particle.library", "\"\"", Wording{Sentence::kLibraryPathEmpty, {}});
  }
  const FileList files = list_all_files(options.paths);
  std::vector<Outcome> outcomes(files.size());
  parallel_for_index(0, files.size(), [&](std::size_t i) {
    outcomes[i] = import_file(files[i].first, files[i].second, options.import);
  });
  ShapeLibrary library;
  library.source = options.paths_text();
  library.units = options.import.units;
  library.shapes.reserve(files.size());
  const Outcome* first_skipped = nullptr;
  for (std::size_t i = 0; i < files.size(); ++i) {
    Outcome& outcome = outcomes[i];
    if (outcome.shape) {
      library.shapes.push_back(std::move(*outcome.shape));
      continue;
    }
    if (!options.is_skipping_bad) {
      Error error(outcome.kind, outcome.wording);
      for (WordedValue& worded : outcome.worded) {
        error.word_value(std::move(worded.text), std::move(worded.wording));
      }
      throw error;
    }
    library.skipped.push_back(files[i].second + ": " + outcome.message);
    if (first_skipped == nullptr) first_skipped = &outcome;
  }
  if (library.shapes.empty()) {
    const std::string first = clipped(library.skipped.front(), 160);
    InvalidInput error(
        "particle.library", aggpack::quoted(library.source),
        Wording{Sentence::kLibraryAllSkipped, {std::to_string(files.size()), first}});
    // The first file's reason in its own sentence (it names the file by its path).
    if (first_skipped != nullptr) {
      error.word_value(first, first_skipped->wording);
      for (const WordedValue& worded : first_skipped->worded) {
        error.word_value(worded.text, worded.wording);
      }
    }
    throw error;
  }
  return library;
}

}  // namespace aggpack
