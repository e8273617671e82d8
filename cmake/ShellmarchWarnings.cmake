# Warnings for the project's own targets (not third-party code).
function(shellmarch_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wno-missing-field-initializers)
endfunction()
