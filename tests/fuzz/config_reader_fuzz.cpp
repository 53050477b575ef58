// libFuzzer target for the configuration reader (issue 12): the bytes are TOML text, then
// optionally `--set` strings, each introduced by a NUL byte ("text\0packer.gap=1\0seed=2").
// Every aggpack::Error is a correct answer. A configuration that is accepted must give the same
// resolved TOML when its resolved TOML is parsed again (config.h promises the round trip); a
// difference aborts, as do crashes, sanitizer reports, leaks, timeouts and out-of-memory.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "aggpack/config/config.h"
#include "config_fuzz_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return aggpack::fuzz::check_config_round_trip(
      data, size,
      [](std::string_view text, std::string_view name, const std::vector<std::string>& overrides) {
        return aggpack::parse_pack_config(text, name, overrides).resolved_toml;
      });
}
