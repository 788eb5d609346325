# Writes OUTPUT (a C++ source defining coshell::git_commit) from the git
# state of SOURCE_DIR, at build time, so that summary.json always names the
# commit the binary was built from ("+modified" when source/ or include/
# differ from it). The file is rewritten only when the text changes, so an
# unchanged commit triggers no recompilation.
execute_process(COMMAND git rev-parse --short HEAD
                WORKING_DIRECTORY ${SOURCE_DIR}
                OUTPUT_VARIABLE commit
                OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
execute_process(COMMAND git status --porcelain --untracked-files=no -- source include
                WORKING_DIRECTORY ${SOURCE_DIR}
                OUTPUT_VARIABLE changes
                OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
if(NOT commit)
  set(commit unknown)
elseif(changes)
  string(APPEND commit "+modified")
endif()
set(text "namespace coshell\n{\n  extern const char *const git_commit = \"${commit}\";\n}\n")
if(EXISTS ${OUTPUT})
  file(READ ${OUTPUT} previous)
endif()
if(NOT "${previous}" STREQUAL "${text}")
  file(WRITE ${OUTPUT} "${text}")
endif()
