# tellus_set_warnings(target): the project's warning set, applied to every first-party target.
function(tellus_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wshadow -Wnon-virtual-dtor
                                           -Wold-style-cast -Wcast-align -Wunused
                                           -Woverloaded-virtual -Wpedantic -Wconversion
                                           -Wno-sign-conversion)
endfunction()
