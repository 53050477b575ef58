// libFuzzer target for the repose / sweep configuration reader: the bytes are TOML text, then
// optionally `--set` strings, each introduced by a NUL byte, as in config_reader_fuzz.cpp. Every
// aggpack::Error is a correct answer. A configuration that is accepted must give the same
// resolved TOML when its resolved TOML is parsed again (`repose --print-config` prints what the
// run accepts); a difference aborts, as do crashes, sanitizer reports, leaks, timeouts and
// out-of-memory. Built when the simulation module is (the repose keys bind its options).

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

#include "aggpack/config/repose_config.h"
#include "aggpack/core/error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  const std::size_t end_of_text = input.find('\0');
  const std::string_view text = input.substr(0, end_of_text);
  std::vector<std::string> overrides;
  if (end_of_text != std::string_view::npos) {
    std::string_view rest = input.substr(end_of_text + 1);
    while (true) {
      const std::size_t next = rest.find('\0');
      overrides.emplace_back(rest.substr(0, next));
      if (next == std::string_view::npos) break;
      rest = rest.substr(next + 1);
    }
  }
  std::string resolved;
  try {
    resolved =
        aggpack::resolved_sweep_config(aggpack::parse_sweep_config(text, "fuzz.toml", overrides));
  } catch (const aggpack::Error&) {
    return 0;
  }
  std::string again;
  try {
    again = aggpack::resolved_sweep_config(aggpack::parse_sweep_config(resolved, "resolved"));
  } catch (const aggpack::Error& error) {
    std::fprintf(stderr, "resolved configuration rejected: %s\n--- resolved ---\n%s\n",
                 error.what(), resolved.c_str());
    std::abort();
  }
  if (again != resolved) {
    std::fprintf(stderr,
                 "round trip changed the configuration\n--- first ---\n%s\n--- again ---\n%s\n",
                 resolved.c_str(), again.c_str());
    std::abort();
  }
  return 0;
}
