# MPI (issue 15 item 6): `mpirun -n N aggpack sweep|repose --seeds ...` splits the runs over the
# ranks (rank r acts as --case r+1 --of N) and rank 0 merges. Optional: ON when an MPI C library
# is found (Debian: libopenmpi-dev, openmpi-bin); without it the same split works with
# --case K --of N and `aggpack merge` under any scheduler.
option(AGGPACK_WITH_MPI "Use MPI for `mpirun -n N aggpack sweep|repose --seeds` when found" ON)
if(AGGPACK_WITH_MPI AND TARGET aggpack_sim)
  find_package(MPI COMPONENTS C QUIET)
  if(MPI_C_FOUND)
    target_link_libraries(aggpack PRIVATE MPI::MPI_C)
    target_compile_definitions(aggpack PRIVATE AGGPACK_HAS_MPI=1)
    set(AGGPACK_HAS_MPI ON)  # tests/CMakeLists.txt: test_sim runs the mpirun test
    message(STATUS "aggpack: MPI found (${MPI_C_LIBRARY_NAMES}): mpirun -n N aggpack sweep")
  else()
    message(STATUS "aggpack: MPI not found: no mpirun support (--case K --of N still works)")
  endif()
endif()
