#pragma once
// A small repose trough for CLI tests: 0.05 x 0.02 x 0.04 m, 2 x 2 x 2 = 8 lattice sites of
// R = 5 mm behind the baffle, short stages, so a Bullet run takes well under a second.

#include <string>

namespace aggpack::test {

/// The trough's TOML with `particle_lines` (what the particles are: "alpha = 0.9 ..." or
/// "library = \"rocks\"\n") in its [particle] table; radius 5 mm, fill 0.02 m, seed 3.
inline std::string small_trough(const std::string& particle_lines) {
  return R"([trough]
length = 0.05
width = 0.02
height = 0.04
baffle_position = 0.02
baffle_thickness = 0.005
baffle_speed = 0.2
baffle_clear_time = 0.02
[particle]
)" + particle_lines +
         R"(radius = 0.005
fill_height = 0.02
seed = 3
[physics]
density = 1200
friction = 0.5
[rest]
quiet_time = 0.02
check_interval = 0.005
max_time = 0.3
confirm_window = 2
)";
}

}  // namespace aggpack::test
