#pragma once
// Shared by the configuration readers' libFuzzer targets (config_reader_fuzz.cpp,
// repose_config_fuzz.cpp): how the bytes become a TOML text and `--set` strings, and the round
// trip every accepted configuration must survive.

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

#include "aggpack/core/error.h"

namespace aggpack::fuzz {

// The bytes are TOML text, then optionally `--set` strings, each introduced by a NUL byte
// ("text\0packer.gap=1\0seed=2").
struct ConfigInput {
  std::string_view text;
  std::vector<std::string> overrides;
};

inline ConfigInput split_config_input(const std::uint8_t* data, std::size_t size) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  const std::size_t end_of_text = input.find('\0');
  ConfigInput result{.text = input.substr(0, end_of_text), .overrides = {}};
  if (end_of_text != std::string_view::npos) {
    std::string_view rest = input.substr(end_of_text + 1);
    while (true) {
      const std::size_t next = rest.find('\0');
      result.overrides.emplace_back(rest.substr(0, next));
      if (next == std::string_view::npos) break;
      rest = rest.substr(next + 1);
    }
  }
  return result;
}

// Runs resolve(text, source name, overrides) -> resolved TOML on the input. Every aggpack::Error
// is a correct answer; an accepted configuration must give the same resolved TOML when that TOML
// is resolved again, or this aborts (as do crashes, sanitizer reports, leaks, timeouts, OOM).
template <typename Resolve>
int check_config_round_trip(const std::uint8_t* data, std::size_t size, const Resolve& resolve) {
  const ConfigInput input = split_config_input(data, size);
  std::string resolved;
  try {
    resolved = resolve(input.text, "fuzz.toml", input.overrides);
  } catch (const Error&) {
    return 0;
  }
  std::string again;
  try {
    again = resolve(resolved, "resolved", std::vector<std::string>{});
  } catch (const Error& error) {
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

}  // namespace aggpack::fuzz
