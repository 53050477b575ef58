# Rendering: library aggpack_render (OpenGL 3.3 core drawing of a Packing, headless EGL context,
# PNG output) and the `aggpack render` sub-command. Optional: the core builds without OpenGL.
# Needs (Debian): libegl-dev libgl-dev (libOpenGL + libEGL from libglvnd, Mesa's EGL/llvmpipe at
# run time) and libstb-dev.

option(AGGPACK_BUILD_RENDER "Build headless rendering (aggpack_render, `aggpack render`)" ON)

if(AGGPACK_BUILD_RENDER)
  set(OpenGL_GL_PREFERENCE GLVND)
  find_package(OpenGL QUIET COMPONENTS OpenGL EGL)
  find_package(PkgConfig QUIET)
  if(PkgConfig_FOUND)
    pkg_check_modules(STB QUIET IMPORTED_TARGET stb)
  endif()
  if(NOT TARGET OpenGL::OpenGL OR NOT TARGET OpenGL::EGL OR NOT TARGET PkgConfig::STB)
    message(STATUS "aggpack: rendering disabled (needs libOpenGL, libEGL and stb: "
                   "apt-get install libegl-dev libgl-dev libstb-dev pkg-config)")
    set(AGGPACK_BUILD_RENDER OFF)
  endif()
endif()

if(AGGPACK_BUILD_RENDER)
  file(GLOB AGGPACK_RENDER_SOURCES CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/render/*.cpp)
  add_library(aggpack_render ${AGGPACK_RENDER_SOURCES})
  add_library(aggpack::render ALIAS aggpack_render)
  target_link_libraries(aggpack_render PUBLIC aggpack_core PRIVATE OpenGL::OpenGL OpenGL::EGL
                        PkgConfig::STB)
  target_compile_definitions(aggpack_render PUBLIC AGGPACK_HAS_RENDER=1)
  # `aggpack render` (app/cli/render_commands.cpp compiles to nothing without AGGPACK_HAS_RENDER).
  target_link_libraries(aggpack PRIVATE aggpack_render)
endif()
