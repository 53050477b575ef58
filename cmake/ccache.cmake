# Compiler cache (ccache), on by default when installed: a second build of the same sources --
# `scripts/test.sh` after `scripts/quickstart.sh`, or CI's fresh clone right after a developer's
# own build -- compiles only what changed. The cache lives outside the tree, shared by every
# clone and build folder of the user (AGGPACK_CCACHE_DIR, default ~/.cache/aggpack/ccache, capped
# at AGGPACK_CCACHE_SIZE). base_dir = the source tree and no cwd in the hash, so a clone in
# another folder hits the same entries (no absolute path of the tree reaches a compile command:
# tests get theirs at run time, tests/support/paths.h).
option(AGGPACK_CCACHE "Compile through ccache when it is installed" ON)
set(AGGPACK_CCACHE_DIR "$ENV{HOME}/.cache/aggpack/ccache" CACHE PATH "ccache folder")
set(AGGPACK_CCACHE_SIZE "12G" CACHE STRING "ccache size cap")
if(AGGPACK_CCACHE AND NOT CMAKE_CXX_COMPILER_LAUNCHER)
  find_program(AGGPACK_CCACHE_PROGRAM ccache)
  if(AGGPACK_CCACHE_PROGRAM)
    set(launcher env "CCACHE_DIR=${AGGPACK_CCACHE_DIR}" "CCACHE_MAXSIZE=${AGGPACK_CCACHE_SIZE}"
                 "CCACHE_BASEDIR=${PROJECT_SOURCE_DIR}" CCACHE_NOHASHDIR=1
                 "${AGGPACK_CCACHE_PROGRAM}")
    set(CMAKE_C_COMPILER_LAUNCHER ${launcher})
    set(CMAKE_CXX_COMPILER_LAUNCHER ${launcher})
    # No cwd in the hash: an object cached from another clone keeps that clone's folder in its
    # debug information (the sanitized build's -g1 line tables), so a stack trace may name the
    # other clone's path for a file; its line numbers are right, the sources being the same.
  endif()
endif()
