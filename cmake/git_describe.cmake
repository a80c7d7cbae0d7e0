# Run at every build (not at configure time): writes OUT with the source tree's `git describe`, and
# only when it changed, so a new commit recompiles version.cpp alone and an unchanged tree nothing.
# cmake -DSOURCE_DIR=... -DOUT=.../git_describe.h -P git_describe.cmake
execute_process(COMMAND git describe --always --dirty --tags
                WORKING_DIRECTORY ${SOURCE_DIR}
                OUTPUT_VARIABLE describe OUTPUT_STRIP_TRAILING_WHITESPACE
                ERROR_QUIET)
if(NOT describe)
  set(describe "unknown")
endif()
set(text "// Generated at build time by cmake/git_describe.cmake.\n#define GRANWAVE_GIT_DESCRIBE \"${describe}\"\n")
set(old "")
if(EXISTS ${OUT})
  file(READ ${OUT} old)
endif()
if(NOT old STREQUAL text)
  file(WRITE ${OUT} "${text}")
endif()
