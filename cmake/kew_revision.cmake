# Run at build time (cmake -P) by the kew_revision target: writes OUT, a header defining
# KEW_REVISION as the source tree's git commit ("-dirty" when tracked files differ from
# it), or REVISION when given (a package built from a tarball), or "unknown". The file is
# rewritten only when the text changes, so an unchanged revision recompiles nothing.
set(revision "${REVISION}")
if(NOT revision AND GIT)
  execute_process(COMMAND "${GIT}" rev-parse --short=12 HEAD WORKING_DIRECTORY "${SOURCE_DIR}"
                  OUTPUT_VARIABLE revision OUTPUT_STRIP_TRAILING_WHITESPACE RESULT_VARIABLE failed ERROR_QUIET)
  if(failed OR NOT revision)
    set(revision "unknown")
  else()
    execute_process(COMMAND "${GIT}" status --porcelain --untracked-files=no WORKING_DIRECTORY "${SOURCE_DIR}"
                    OUTPUT_VARIABLE changes RESULT_VARIABLE failed ERROR_QUIET)
    if(NOT failed AND changes)
      string(APPEND revision "-dirty")
    endif()
  endif()
endif()
if(NOT revision)
  set(revision "unknown")
endif()
file(CONFIGURE OUTPUT "${OUT}" CONTENT "#define KEW_REVISION \"${revision}\"\n" @ONLY)
