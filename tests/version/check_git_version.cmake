# ctest h5md.creator_version: cmake/GitVersion.cmake, which gives /h5md/creator@version and
# `granular-dsmc --version` (\ref output_h5md "docs/output.md").
#   cmake -DSOURCE_DIR=<source tree> -DWORK=<scratch directory> -DVERSION=<project version> -P check_git_version.cmake
# 1. a tree that is not a git checkout of its own (a tarball; here a directory in the build tree, which
#    may itself lie inside a checkout) gives the project's version alone;
# 2. the source tree gives VERSION+<git describe --always --dirty --tags> when git is installed and the
#    tree is the top of a checkout, else VERSION;
# 3. a second run at an unchanged version leaves the header untouched (no recompilation).
set(script ${SOURCE_DIR}/cmake/GitVersion.cmake)
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK}/tarball)

function(version_of tree header out)
  execute_process(COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${tree} -DOUTPUT=${header} -DFALLBACK_VERSION=${VERSION}
                          -P ${script} RESULT_VARIABLE result)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "GitVersion.cmake failed for ${tree}")
  endif()
  file(STRINGS ${header} line REGEX "#define GDSMC_BUILD_VERSION")
  string(REGEX REPLACE "^#define GDSMC_BUILD_VERSION \"(.*)\"$" "\\1" version "${line}")
  set(${out} "${version}" PARENT_SCOPE)
endfunction()

version_of(${WORK}/tarball ${WORK}/tarball.hpp tarball)
if(NOT tarball STREQUAL VERSION)
  message(FATAL_ERROR "a tree without a checkout of its own gives '${tarball}', expected '${VERSION}'")
endif()

set(expected ${VERSION})
find_program(GIT git)
if(GIT)
  execute_process(COMMAND ${GIT} rev-parse --show-toplevel WORKING_DIRECTORY ${SOURCE_DIR}
                  RESULT_VARIABLE r OUTPUT_VARIABLE top OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
  if(r EQUAL 0)
    file(REAL_PATH "${top}" top)
    file(REAL_PATH "${SOURCE_DIR}" source)
    if(top STREQUAL source)
      execute_process(COMMAND ${GIT} describe --always --dirty --tags WORKING_DIRECTORY ${SOURCE_DIR}
                      OUTPUT_VARIABLE describe OUTPUT_STRIP_TRAILING_WHITESPACE)
      set(expected "${VERSION}+${describe}")
    endif()
  endif()
endif()
version_of(${SOURCE_DIR} ${WORK}/source.hpp source_version)
if(NOT source_version STREQUAL expected)
  message(FATAL_ERROR "the source tree gives '${source_version}', expected '${expected}'")
endif()

execute_process(COMMAND touch -d "2001-02-03 04:05:06" ${WORK}/source.hpp)
version_of(${SOURCE_DIR} ${WORK}/source.hpp again)
file(TIMESTAMP ${WORK}/source.hpp stamp "%Y")
if(NOT stamp STREQUAL "2001")
  message(FATAL_ERROR "an unchanged version rewrote the header (it would recompile)")
endif()
message(STATUS "tarball: ${tarball}; source tree: ${source_version}")
