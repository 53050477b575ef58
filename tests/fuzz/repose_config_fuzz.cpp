// libFuzzer target for the repose / sweep configuration reader: the bytes are TOML text, then
// optionally `--set` strings, each introduced by a NUL byte, as in config_reader_fuzz.cpp. Every
// aggpack::Error is a correct answer. A configuration that is accepted must give the same
// resolved TOML when its resolved TOML is parsed again (`repose --print-config` prints what the
// run accepts); a difference aborts, as do crashes, sanitizer reports, leaks, timeouts and
// out-of-memory. Built when the simulation module is (the repose keys bind its options).

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "aggpack/config/repose_config.h"
#include "config_fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return aggpack::fuzz::check_config_round_trip(
      data, size,
      [](std::string_view text, std::string_view name, const std::vector<std::string>& overrides) {
        return aggpack::resolved_sweep_config(aggpack::parse_sweep_config(text, name, overrides));
      });
}
