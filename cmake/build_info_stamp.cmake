# Run by the build on every build (cmake/build_info.cmake):
#   cmake -DSOURCE_DIR=... -DOUTPUT=file.cpp -DVERSION=x.y.z [-DGIT=/usr/bin/git] -P build_info_stamp.cmake
# Writes OUTPUT, defining rayster::app::buildCommit() and buildVersion(), only when its contents
# change, so an unchanged tree compiles and links nothing.
#
# The commit is `git rev-parse --short HEAD` of SOURCE_DIR, with "-dirty" when tracked files differ
# from HEAD (untracked files do not count, as with `git describe --dirty`); "unknown" without git,
# or when SOURCE_DIR is not the top of a work tree (a source archive unpacked inside some other
# repository must not report that repository's commit).
cmake_minimum_required(VERSION 3.25)
foreach(var SOURCE_DIR OUTPUT VERSION)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "build_info_stamp.cmake: -D${var}=... is required")
  endif()
endforeach()

set(commit unknown)
if(GIT)
  # Read-only: `git status` would otherwise refresh the index under a lock that a concurrent git
  # command in the same work tree may hold.
  set(ENV{GIT_OPTIONAL_LOCKS} 0)
  execute_process(COMMAND ${GIT} -C ${SOURCE_DIR} rev-parse --show-toplevel
                  RESULT_VARIABLE rc OUTPUT_VARIABLE top OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
  file(REAL_PATH "${SOURCE_DIR}" source_real)
  if(rc EQUAL 0 AND NOT top STREQUAL "")
    file(REAL_PATH "${top}" top_real)
  endif()
  if(rc EQUAL 0 AND NOT top STREQUAL "" AND top_real STREQUAL source_real)
    execute_process(COMMAND ${GIT} -C ${SOURCE_DIR} rev-parse --short HEAD
                    RESULT_VARIABLE rc OUTPUT_VARIABLE hash OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
    if(rc EQUAL 0 AND NOT hash STREQUAL "")
      set(commit ${hash})
      execute_process(COMMAND ${GIT} -C ${SOURCE_DIR} status --porcelain --untracked-files=no
                      RESULT_VARIABLE rc OUTPUT_VARIABLE changes ERROR_QUIET)
      if(NOT rc EQUAL 0 OR NOT changes STREQUAL "")
        string(APPEND commit -dirty)  # a failed status cannot vouch for a clean tree
      endif()
    endif()
  endif()
endif()

set(text "// Generated at build time by cmake/build_info_stamp.cmake from ${SOURCE_DIR}; do not edit.
namespace rayster::app {
const char* buildCommit() { return \"${commit}\"; }
const char* buildVersion() { return \"${VERSION}\"; }
}  // namespace rayster::app
")
if(EXISTS ${OUTPUT})
  file(READ ${OUTPUT} old)
endif()
if(NOT "${old}" STREQUAL "${text}")
  file(WRITE ${OUTPUT} "${text}")
  message(STATUS "build info: ${commit}")
endif()
