# prt_set_warnings(target): the project's warning set, applied to its own targets only.
function(prt_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wconversion
    -Wno-sign-conversion -Wnon-virtual-dtor -Wcast-align -Woverloaded-virtual)
endfunction()
