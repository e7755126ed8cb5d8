# The quick tests figures.help.<script> (paper-figures/CMakeLists.txt): `python3 SCRIPT -h` and
# `python3 SCRIPT --help`, run in an empty directory, exit 0, print the usage and write nothing there.
# HOME, MPLCONFIGDIR and the XDG directories point into that directory too: a script that loaded
# matplotlib for --help (which creates its config directory and a font cache) would fail here.
#
#   cmake -DPYTHON=/usr/bin/python3 -DSCRIPT=paper-figures/seed000.py -DWORK=<directory> -P help_test.cmake
#
# WORK is emptied first and removed when the test passes (kept for a look when it fails).
foreach(var PYTHON SCRIPT WORK)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "help_test.cmake: -D${var}=... is missing")
  endif()
endforeach()
get_filename_component(name "${SCRIPT}" NAME)
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")

foreach(flag -h --help)
  # PYTHONDONTWRITEBYTECODE: a test leaves no __pycache__ in the source tree either
  execute_process(
    COMMAND "${CMAKE_COMMAND}" -E env HOME=${WORK} MPLCONFIGDIR=${WORK} XDG_CONFIG_HOME=${WORK}
            XDG_CACHE_HOME=${WORK} PYTHONDONTWRITEBYTECODE=1 "${PYTHON}" "${SCRIPT}" ${flag}
    WORKING_DIRECTORY "${WORK}" RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${name} ${flag}: exit status ${rc} (expected 0)\n${out}${err}")
  endif()
  string(FIND "${out}" "usage: ${name} " at)
  string(FIND "${out}" "--run CASE=FILE" run_option)
  if(NOT at EQUAL 0 OR run_option LESS 0)
    message(FATAL_ERROR "${name} ${flag}: no usage (usage: ${name} ... --run CASE=FILE) on stdout:\n${out}")
  endif()
  if(NOT err STREQUAL "")
    message(FATAL_ERROR "${name} ${flag}: wrote to stderr:\n${err}")
  endif()
  file(GLOB_RECURSE written LIST_DIRECTORIES true "${WORK}/*")
  if(written)
    message(FATAL_ERROR "${name} ${flag} wrote files or directories (in ${WORK}): ${written}")
  endif()
  message(STATUS "${name} ${flag}: usage printed, exit status 0, nothing written")
endforeach()
file(REMOVE_RECURSE "${WORK}")
