# Run at every build (reports/CMakeLists.txt): writes OUT with the git revision of the sources
# being built and whether they differ from it, so run.json names the code the binary was built
# from, not the code at configure time. Rewrites OUT only when it changes (no needless rebuilds).
execute_process(COMMAND git rev-parse --short=12 HEAD WORKING_DIRECTORY ${SRC}
                OUTPUT_VARIABLE rev OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET RESULT_VARIABLE rc)
if(NOT rc EQUAL 0 OR NOT rev)
  set(rev "unknown")
  set(dirty 0)
else()
  execute_process(COMMAND git status --porcelain --untracked-files=no WORKING_DIRECTORY ${SRC}
                  OUTPUT_VARIABLE changes OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
  if(changes)
    set(dirty 1)
  else()
    set(dirty 0)
  endif()
endif()
set(text "// Generated at build time by reports/build_info.cmake.\n#define MESHREUSE_GIT_REV \"${rev}\"\n#define MESHREUSE_GIT_DIRTY ${dirty}\n")
if(EXISTS ${OUT})
  file(READ ${OUT} old)
else()
  set(old "")
endif()
if(NOT old STREQUAL text)
  file(WRITE ${OUT} "${text}")
endif()
