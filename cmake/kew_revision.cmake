# Run at build time (cmake -P) by the kew_revision target: writes OUT, a header defining
# KEW_REVISION as REVISION when given, else the source tree's git commit ("-dirty" when
# tracked files differ from it), else FALLBACK when given (a package built from a source
# tree without git names its own version: debian/rules), else "unknown". The file is
# rewritten only when the text changes, so an unchanged revision recompiles nothing.
set(revision "${REVISION}")
if(NOT revision AND GIT)
  # The tree's own repository only: a tarball unpacked inside another checkout is not it.
  execute_process(COMMAND "${GIT}" rev-parse --show-toplevel WORKING_DIRECTORY "${SOURCE_DIR}"
                  OUTPUT_VARIABLE top OUTPUT_STRIP_TRAILING_WHITESPACE RESULT_VARIABLE failed ERROR_QUIET)
  if(NOT failed)
    file(REAL_PATH "${top}" top)
    file(REAL_PATH "${SOURCE_DIR}" source)
  endif()
  if(NOT failed AND top STREQUAL source)
    execute_process(COMMAND "${GIT}" rev-parse --short=12 HEAD WORKING_DIRECTORY "${SOURCE_DIR}"
                    OUTPUT_VARIABLE revision OUTPUT_STRIP_TRAILING_WHITESPACE RESULT_VARIABLE failed ERROR_QUIET)
    if(failed)
      set(revision "")
    elseif(revision)
      execute_process(COMMAND "${GIT}" status --porcelain --untracked-files=no WORKING_DIRECTORY "${SOURCE_DIR}"
                      OUTPUT_VARIABLE changes RESULT_VARIABLE failed ERROR_QUIET)
      if(NOT failed AND changes)
        string(APPEND revision "-dirty")
      endif()
    endif()
  endif()
endif()
if(NOT revision)
  set(revision "${FALLBACK}")
endif()
if(NOT revision)
  set(revision "unknown")
endif()
file(CONFIGURE OUTPUT "${OUT}" CONTENT "#define KEW_REVISION \"${revision}\"\n" @ONLY)
