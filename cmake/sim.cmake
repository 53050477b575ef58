# Physics (issue 6): the Bullet bridge, gravity settling, the angle-of-repose trough test and
# sweeps, as the library aggpack_sim (src/sim/*.cpp). Optional: ON by default when Bullet's
# double-precision build is found (Debian libbullet-dev ships it as bullet-float64); without it
# the rest of aggpack builds and the CLI has no settle/repose/sweep commands.
# Included from the top-level CMakeLists.txt after the `aggpack` executable is defined.

find_package(PkgConfig QUIET)
if(PkgConfig_FOUND)
  # Double precision: particles of 10 mm in a metre-scale trough, and exact-geometry checks.
  pkg_check_modules(BULLET IMPORTED_TARGET bullet-float64)
endif()
set(_aggpack_sim_default OFF)
if(BULLET_FOUND)
  set(_aggpack_sim_default ON)
endif()
option(AGGPACK_BUILD_SIM "Build the Bullet physics module (settle, repose, sweep)"
       ${_aggpack_sim_default})

if(AGGPACK_BUILD_SIM)
  if(NOT BULLET_FOUND)
    message(FATAL_ERROR "AGGPACK_BUILD_SIM=ON needs Bullet (apt-get install libbullet-dev)")
  endif()
  find_package(nlohmann_json REQUIRED)
  message(STATUS "Bullet ${BULLET_VERSION} (double precision): building aggpack_sim")

  # The option words and seed lists (no Bullet): what the configuration module (the repose and
  # sweep keys) needs, so that it, and the fuzz targets built on it, do not compile the physics.
  set(_aggpack_sim_words ${PROJECT_SOURCE_DIR}/src/sim/option_words.cpp)
  add_library(aggpack_sim_words ${_aggpack_sim_words})
  target_link_libraries(aggpack_sim_words PUBLIC aggpack_core)
  target_compile_definitions(aggpack_sim_words PUBLIC AGGPACK_HAS_SIM=1)

  file(GLOB AGGPACK_SIM_SOURCES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/sim/*.cpp)
  list(REMOVE_ITEM AGGPACK_SIM_SOURCES ${_aggpack_sim_words})
  add_library(aggpack_sim ${AGGPACK_SIM_SOURCES})
  add_library(aggpack::sim ALIAS aggpack_sim)
  target_link_libraries(aggpack_sim PUBLIC aggpack_sim_words aggpack_core
                        PRIVATE PkgConfig::BULLET nlohmann_json::nlohmann_json)

  target_link_libraries(aggpack PRIVATE aggpack_sim)
  # `aggpack repose CONFIG.toml` and `aggpack sweep CONFIG.toml` parse their own tables.
  target_link_libraries(aggpack PRIVATE tomlplusplus::tomlplusplus)
endif()
