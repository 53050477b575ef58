#pragma once
// Output flags checked alike in every command: `-o ""` and an output file that is a folder (or,
// for folder outputs, a file) give the same one-line error. README "Errors".

#include <cstdint>
#include <string>
#include <string_view>

namespace aggpack::cli {

/// An output FILE flag's value (`-o`, `--table`, ...): "" is bad input (InvalidInput naming
/// `flag`, exit 2); an existing folder ("refusing to replace PATH: not a regular file
/// (directory)", as AtomicFile says) or a path ending in '/' is an unwritable path (IoError, exit
/// 3). Call before any work.
void check_output_file_flag(std::string_view flag, const std::string& path);

/// An output FOLDER flag's value (repose -o, export --per-particle): "" is bad input; an
/// existing file that is not a folder is an unwritable path.
void check_output_folder_flag(std::string_view flag, const std::string& path);

/// A --seed value as typed: an integer in [0, 2^63 - 1] (the range of packer.seed and
/// particle.seed). Taken as text because CLI11 would wrap "-1" to 2^64 - 1; anything else is
/// InvalidInput naming `flag` (exit 2).
std::uint64_t parse_seed_flag(std::string_view flag, const std::string& text);

}  // namespace aggpack::cli
