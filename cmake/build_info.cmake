# The commit a binary was built from, stamped by every build rather than read once at configure
# time: `rayster --version`, `render --json` and bench JSON must name the tree that was compiled,
# and a configure-time value goes stale at the first commit after `cmake -S . -B build`.
#
# rayster_build_info(TARGET SOURCE_DIR VERSION) makes a static library TARGET whose one source is
# generated into the build folder by cmake/build_info_stamp.cmake. A custom target runs that
# script on every build (custom targets are always out of date); the script rewrites the source
# only when the stamp changed, and the generated file is a BYPRODUCT, so Ninja re-checks its time
# stamp after the step (restat) and compiles and relinks only after a real change.
#
# The library defines rayster::app::buildCommit() and buildVersion() (app/build_info.h).
set(RAYSTER_BUILD_INFO_SCRIPT ${CMAKE_CURRENT_LIST_DIR}/build_info_stamp.cmake)

function(rayster_build_info target source_dir version)
  find_package(Git QUIET)  # none: the stamp says "unknown"
  set(out ${CMAKE_CURRENT_BINARY_DIR}/generated/${target}.cpp)
  add_custom_target(${target}_stamp ALL
    COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${source_dir} -DOUTPUT=${out} -DVERSION=${version}
            -DGIT=${GIT_EXECUTABLE} -P ${RAYSTER_BUILD_INFO_SCRIPT}
    BYPRODUCTS ${out}
    COMMENT "Stamping the commit of ${source_dir}"
    VERBATIM)
  add_library(${target} STATIC ${out})
  add_dependencies(${target} ${target}_stamp)
endfunction()
