#pragma once
// Why a file cannot be read, in the user's words: a typo (no such file) and a permission are fixed
// apart, so only ENOENT is "no such file" and EACCES is "permission denied" (as read_config_file).

#include <cerrno>
#include <cstring>
#include <string>
#include "aggpack/core/error_words.h"

namespace aggpack::io_detail {

/// The wording of "cannot read `path`" for the errno `reason` of a failed stat or open.
inline Wording read_failure_wording(const std::string& path, int reason) {
  if (reason == ENOENT) return Wording{Sentence::kReadNoSuchFile, {path}};
  if (reason == EACCES) return Wording{Sentence::kReadPermission, {path}};
  return Wording{Sentence::kReadSystemError,
                 {path, reason != 0 ? std::string(std::strerror(reason)) : "cannot open it"}};
}

}  // namespace aggpack::io_detail
