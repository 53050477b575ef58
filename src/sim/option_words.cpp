// The simulation's option words and seed lists, apart from Bullet: the configuration module
// (repose and sweep keys) and the fuzz targets use them without building the physics
// (cmake/sim.cmake: library aggpack_sim_words).

#include <charconv>
#include <cstdint>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "aggpack/core/error.h"
#include "aggpack/core/text.h"
#include "aggpack/sim/distributed.h"
#include "aggpack/sim/ensemble.h"
#include "aggpack/sim/repose.h"
#include "aggpack/sim/world.h"

namespace aggpack {

namespace {

std::uint64_t parse_seed(const std::string& token, const std::string& field,
                         const std::string& text) {
  std::uint64_t value = 0;
  const char* end = token.data() + token.size();
  const auto [ptr, error] = std::from_chars(token.data(), end, value);
  if (token.empty() || error != std::errc() || ptr != end) {
    throw InvalidInput(field, "\"" + text + "\"",
                       "seeds as non-negative integers: a range 1-16, a list 1,4,9 or both");
  }
  return value;
}

}  // namespace

std::vector<std::uint64_t> parse_seed_list(const std::string& text, const std::string& field) {
  std::vector<std::uint64_t> seeds;
  std::set<std::uint64_t> seen;
  const auto add = [&](std::uint64_t seed) {
    if (!seen.insert(seed).second) {
      throw InvalidInput(field, "\"" + text + "\"",
                         "each seed once (" + std::to_string(seed) + " repeats)");
    }
    seeds.push_back(seed);
  };
  if (text.empty()) {
    throw InvalidInput(field, "\"\"", "a range 1-16, a list 1,4,9 or both (1-4,9)");
  }
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    const std::string token = text.substr(start, comma - start);
    const std::size_t dash = token.find('-');
    if (dash == std::string::npos) {
      add(parse_seed(token, field, text));
    } else {
      const std::uint64_t first = parse_seed(token.substr(0, dash), field, text);
      const std::uint64_t last = parse_seed(token.substr(dash + 1), field, text);
      if (last < first) {
        throw InvalidInput(field, "\"" + text + "\"",
                           "ranges first-last with first <= last (" + token + " is reversed)");
      }
      if (last - first >= kMaxEnsembleSeeds) {
        throw InvalidInput(field, "\"" + text + "\"",
                           "at most " + std::to_string(kMaxEnsembleSeeds) + " seeds");
      }
      for (std::uint64_t seed = first;; ++seed) {
        add(seed);
        if (seeds.size() > kMaxEnsembleSeeds) break;
        if (seed == last) break;
      }
    }
    if (seeds.size() > kMaxEnsembleSeeds) {
      throw InvalidInput(field, "\"" + text + "\"",
                         "at most " + std::to_string(kMaxEnsembleSeeds) + " seeds");
    }
    start = comma + 1;
  }
  return seeds;
}

std::string format_seed_list(const std::vector<std::uint64_t>& seeds) {
  std::string text;
  for (std::size_t i = 0; i < seeds.size();) {
    std::size_t j = i;
    while (j + 1 < seeds.size() && seeds[j + 1] == seeds[j] + 1) ++j;
    if (!text.empty()) text += ',';
    text += std::to_string(seeds[i]);
    if (j > i) text += '-' + std::to_string(seeds[j]);
    i = j + 1;
  }
  return text;
}

std::string_view to_string(ReposeEngine engine) {
  return engine == ReposeEngine::kYade ? "yade" : "bullet";
}

ReposeEngine repose_engine_from_string(std::string_view word) {
  if (word == "bullet") return ReposeEngine::kBullet;
  if (word == "yade") return ReposeEngine::kYade;
  throw InvalidInput("repose.engine", clipped(std::string(word), 40), "bullet or yade");
}

const char* to_string(SolverKind kind) {
  return kind == SolverKind::kBlocked ? "blocked" : "gauss-seidel";
}

SolverKind solver_kind_from_string(const std::string& word, const std::string& key) {
  if (word == "gauss-seidel") return SolverKind::kGaussSeidel;
  if (word == "blocked") return SolverKind::kBlocked;
  throw InvalidInput(key, word, "gauss-seidel or blocked");
}

}  // namespace aggpack
