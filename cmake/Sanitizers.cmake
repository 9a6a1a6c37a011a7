# DEPTHTRACK_SANITIZE: every target with ASan + UBSan, float-cast-overflow included, and no recovery,
# so that any report fails the test that triggered it. DEPTHTRACK_FUZZ: coverage for libFuzzer too.
# DEPTHTRACK_FUZZ_ASAN=OFF leaves ASan out of a fuzz build (UBSan stays): for the mesh campaign, whose
# parser (Debian's assimp) is not instrumented anyway, and whose 16 MiB read buffer per OBJ import costs
# ASan's allocator a fresh mmap and 4,096 page faults each time (~30 ms, against ~2 ms without).
set(DEPTHTRACK_SANITIZER_FLAGS "")
if(DEPTHTRACK_SANITIZE OR (DEPTHTRACK_FUZZ AND DEPTHTRACK_FUZZ_ASAN))
  list(APPEND DEPTHTRACK_SANITIZER_FLAGS -fsanitize=address,undefined,float-cast-overflow -fno-sanitize-recover=all
       -fno-omit-frame-pointer)
elseif(DEPTHTRACK_FUZZ)
  list(APPEND DEPTHTRACK_SANITIZER_FLAGS -fsanitize=undefined,float-cast-overflow -fno-sanitize-recover=all
       -fno-omit-frame-pointer)
endif()
if(DEPTHTRACK_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    message(FATAL_ERROR "DEPTHTRACK_FUZZ needs clang (libFuzzer): configure with -DCMAKE_CXX_COMPILER=clang++")
  endif()
  list(APPEND DEPTHTRACK_SANITIZER_FLAGS -fsanitize=fuzzer-no-link)
endif()
if(DEPTHTRACK_SANITIZER_FLAGS)
  add_compile_options(${DEPTHTRACK_SANITIZER_FLAGS})
  add_link_options(${DEPTHTRACK_SANITIZER_FLAGS})
endif()
