// libFuzzer target for the native reader (issue 12): the bytes are a native packing file, read the
// way `aggpack info` reads it -- read_packing(), the stored configuration parsed for its grading,
// and the statistics. Every aggpack::Error is a correct answer; a crash, sanitizer report, leak,
// timeout or out-of-memory is a finding. Built by scripts/fuzz.sh (CMake option
// AGGPACK_BUILD_FUZZ).

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "aggpack/config/config.h"
#include "aggpack/core/error.h"
#include "aggpack/io/native.h"
#include "aggpack/pack/statistics.h"

namespace {

// HDF5 reads files by name: the input goes to one scratch file per process, in /dev/shm when it
// exists (no disk traffic), rewritten for every input.
const std::string& scratch_path() {
  static const std::string path = [] {
    const char* dir = access("/dev/shm", W_OK) == 0 ? "/dev/shm" : std::getenv("TMPDIR");
    std::string pattern = std::string(dir != nullptr ? dir : "/tmp") + "/aggpack-fuzz-XXXXXX";
    const int fd = mkstemp(pattern.data());
    if (fd < 0) std::abort();
    close(fd);
    std::atexit([] { std::remove(scratch_path().c_str()); });
    return pattern;
  }();
  return path;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string& path = scratch_path();
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (file == nullptr) std::abort();
  if (size > 0 && std::fwrite(data, 1, size, file) != size) std::abort();
  std::fclose(file);
  try {
    const aggpack::Packing packing = aggpack::read_packing(path);
    aggpack::StatisticsOptions options;
    try {
      options.target = aggpack::parse_pack_config(packing.provenance.config_toml, "stored config")
                           .target_grading();
    } catch (const aggpack::Error&) {
    }
    (void)aggpack::compute_statistics(packing, options);
  } catch (const aggpack::Error&) {
  }
  return 0;
}
