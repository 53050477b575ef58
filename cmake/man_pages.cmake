# Script mode (cmake -P), run by the build when help2man is installed: man pages for `aggpack`
# and each of its subcommands (aggpack-pack(1), ... as git does), made by help2man from the
# program's own --help, so they cannot drift from the CLI.
#   cmake -DAGGPACK=path/to/aggpack -DVERSION=0.1.0 -DOUT=build/man -P cmake/man_pages.cmake
foreach(var AGGPACK VERSION OUT)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "man_pages.cmake needs -D${var}=...")
  endif()
endforeach()
find_program(HELP2MAN help2man REQUIRED)
file(MAKE_DIRECTORY "${OUT}")
execute_process(COMMAND "${AGGPACK}" --help OUTPUT_VARIABLE help RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "${AGGPACK} --help failed (${status})")
endif()
# Subcommands are listed as "  name   description" after the "Subcommands:" line.
string(REGEX REPLACE ".*\nSubcommands:\n" "" listing "${help}")
string(REGEX MATCHALL "\n  [a-z][a-z0-9-]*  " names "\n${listing}")
set(pages aggpack.1)
set(wrapper_dir "${OUT}/wrappers")
file(MAKE_DIRECTORY "${wrapper_dir}")
function(make_page program name summary)
  execute_process(
    COMMAND "${HELP2MAN}" --no-info --no-discard-stderr "--version-string=${VERSION}"
            "--name=${summary}" --section=1 --output "${OUT}/${name}.1" "${program}"
    RESULT_VARIABLE page_status)
  if(NOT page_status EQUAL 0)
    message(FATAL_ERROR "help2man failed for ${name}")
  endif()
endfunction()
make_page("${AGGPACK}" aggpack "random aggregate generation and packing")
foreach(entry IN LISTS names)
  string(STRIP "${entry}" sub)
  # help2man runs one program: a two-line wrapper runs `aggpack SUB`.
  set(wrapper "${wrapper_dir}/aggpack-${sub}")
  file(WRITE "${wrapper}" "#!/bin/sh\nexec \"${AGGPACK}\" ${sub} \"$@\"\n")
  file(CHMOD "${wrapper}" PERMISSIONS OWNER_READ OWNER_WRITE OWNER_EXECUTE GROUP_READ
       GROUP_EXECUTE WORLD_READ WORLD_EXECUTE)
  # The one-line summary: the subcommand's description up to its first full stop.
  string(REGEX MATCH "\n  ${sub}  +([^\n]*)" line "\n${listing}")
  string(REGEX REPLACE "^\n  ${sub}  +" "" summary "${line}")
  string(REGEX REPLACE "[.;:(].*" "" summary "${summary}")
  string(TOLOWER "${summary}" summary)
  make_page("${wrapper}" "aggpack-${sub}" "${summary}")
  list(APPEND pages "aggpack-${sub}.1")
endforeach()
file(REMOVE_RECURSE "${wrapper_dir}")
# Debian installs man pages compressed (gzip -n: no name or time stamp, the same bytes each build).
foreach(page IN LISTS pages)
  execute_process(COMMAND gzip -9nf "${OUT}/${page}" RESULT_VARIABLE gzip_status)
  if(NOT gzip_status EQUAL 0)
    message(FATAL_ERROR "gzip failed for ${page}")
  endif()
endforeach()
list(JOIN pages "\n" page_list)
file(WRITE "${OUT}/pages.txt" "${page_list}\n")
