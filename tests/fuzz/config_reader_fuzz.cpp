// libFuzzer target for the configuration reader (issue 12): the bytes are TOML text, then
// optionally `--set` strings, each introduced by a NUL byte ("text\0packer.gap=1\0seed=2").
// Every aggpack::Error is a correct answer. A configuration that is accepted must give the same
// resolved TOML when its resolved TOML is parsed again (config.h promises the round trip); a
// difference aborts, as do crashes, sanitizer reports, leaks, timeouts and out-of-memory.

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

#include "aggpack/config/config.h"
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
    resolved = aggpack::parse_pack_config(text, "fuzz.toml", overrides).resolved_toml;
  } catch (const aggpack::Error&) {
    return 0;
  }
  std::string again;
  try {
    again = aggpack::parse_pack_config(resolved, "resolved").resolved_toml;
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
