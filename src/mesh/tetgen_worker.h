// Internal: how a TetGen worker process answers (tetgen.cpp per particle, mesomodel_tetgen.cpp for
// a whole specimen). The answer is 'M' and the result's bytes (arrays as they are in memory:
// parent and worker are the same program), or 'F' and what TetGen reported.
#pragma once

#include <string>
#include <vector>

#include "aggpack/core/isolated.h"

namespace aggpack::detail {

/// What TetGen did wrong, as the worker reports it.
struct TetGenFailure {
  std::string what;
};

/// Appends the array's bytes as they are in memory.
template <class T>
void append_array(std::string& out, const std::vector<T>& values) {
  out.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
}

/// The worker's answer for `mesh()` (the result's bytes; may throw TetGenFailure).
template <class Mesh>
std::string worker_answer(const Mesh& mesh) {
  try {
    return 'M' + mesh();
  } catch (const TetGenFailure& failure) {
    return 'F' + failure.what;
  }
}

/// The result's bytes of an answered outcome, or false with `failure` saying why not ("TetGen
/// died of signal 6 (Aborted)", TetGen's own report, or a malformed answer).
inline bool worker_result(const IsolatedOutcome& outcome, std::string& bytes,
                          std::string& failure) {
  if (!outcome.is_done) {
    failure = "TetGen " + outcome.failure;
    return false;
  }
  if (!outcome.bytes.empty() && outcome.bytes[0] == 'F') {
    failure = outcome.bytes.substr(1);
    return false;
  }
  if (outcome.bytes.empty() || outcome.bytes[0] != 'M') {
    failure = "malformed result from the worker process";
    return false;
  }
  bytes = outcome.bytes.substr(1);
  return true;
}

}  // namespace aggpack::detail
