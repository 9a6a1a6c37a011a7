# depthtrack_warnings(target): the warning set every target of the project builds with.
function(depthtrack_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor
                                           -Wold-style-cast -Wcast-align -Woverloaded-virtual)
  if(DEPTHTRACK_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()
