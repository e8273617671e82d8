# cmake -DPROGRAM=shellmarch -DHELP2MAN=help2man -DOUT=dir "-DCOMMANDS=info;render;..." -P this
# Writes OUT/shellmarch.1 and OUT/shellmarch-COMMAND.1 with help2man from the program's own
# --help and --version (so the pages cannot disagree with the options), and OUT/shellmarch.bash,
# the bash completion script, from `shellmarch completion bash`.
file(MAKE_DIRECTORY ${OUT}/bin)
set(see_also "")
foreach(c ${COMMANDS})
  string(APPEND see_also ".BR shellmarch-${c} (1),\n")
endforeach()
string(APPEND see_also "and the documents in docs/ of the source tree.\n")
file(WRITE ${OUT}/see-also.h2m "[SEE ALSO]\n${see_also}")

# The version given, not read from `--version`: help2man would take the page's name from that
# line ("shellmarch"), where the executable's name ("shellmarch-render") is wanted.
execute_process(COMMAND ${PROGRAM} --version OUTPUT_VARIABLE version_line
  OUTPUT_STRIP_TRAILING_WHITESPACE)
string(REGEX MATCH "[0-9]+\\.[0-9]+\\.[0-9]+" version "${version_line}")

function(man_page name program description)
  execute_process(COMMAND ${HELP2MAN} --no-info --no-discard-stderr "--name=${description}"
    "--version-string=${version}"
    --include=${OUT}/see-also.h2m --output=${OUT}/${name}.1 ${program}
    RESULT_VARIABLE rc ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "help2man ${name}: ${err}")
  endif()
endfunction()

man_page(shellmarch ${PROGRAM}
  "direct volume rendering of unstructured meshes, data-parallel over MPI")
foreach(c ${COMMANDS})
  # help2man runs a program with --help and --version: a wrapper for each command.
  set(wrapper ${OUT}/bin/shellmarch-${c})
  file(WRITE ${wrapper} "#!/bin/sh\nexec \"${PROGRAM}\" ${c} \"$@\"\n")
  file(CHMOD ${wrapper} PERMISSIONS OWNER_READ OWNER_WRITE OWNER_EXECUTE GROUP_READ
    GROUP_EXECUTE WORLD_READ WORLD_EXECUTE)
  execute_process(COMMAND ${PROGRAM} ${c} --help OUTPUT_VARIABLE help RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${PROGRAM} ${c} --help failed (${rc})")
  endif()
  string(REGEX REPLACE "\n.*" "" first "${help}")  # CLI11: the command's description first
  man_page(shellmarch-${c} ${wrapper} "${first}")
endforeach()

execute_process(COMMAND ${PROGRAM} completion bash OUTPUT_FILE ${OUT}/shellmarch.bash
  RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${PROGRAM} completion bash failed (${rc})")
endif()
