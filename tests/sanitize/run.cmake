# ctest driver: the robustness-critical subset of the suite built with ASan + UBSan (float-cast-overflow
# included, no recovery) and run, so that CI's one test command covers it. The build tree is kept
# (WORK_DIR), so later runs rebuild only what changed. Inputs: SOURCE_DIR, WORK_DIR, GENERATOR,
# CXX_COMPILER, LAUNCHER (may be empty), DATA_DIR.
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}")
  endif()
  message("${out}")
endfunction()
set(launcher "")
if(LAUNCHER)
  set(launcher -DCMAKE_CXX_COMPILER_LAUNCHER=${LAUNCHER})
endif()
run(${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${WORK_DIR} -G ${GENERATOR} -DCMAKE_CXX_COMPILER=${CXX_COMPILER} ${launcher}
    -DCMAKE_BUILD_TYPE=RelWithDebInfo -DDEPTHTRACK_SANITIZE=ON -DDEPTHTRACK_SANITIZE_SUITE=OFF
    -DDEPTHTRACK_BUILD_BENCH=OFF -DDEPTHTRACK_WITH_CUDA=OFF -DDEPTHTRACK_DATA_DIR=${DATA_DIR})
# Two jobs: CI and the development machines have two cores.
run(${CMAKE_COMMAND} --build ${WORK_DIR} -j2 --target depthtrack_sanitized_tests depthtrack_cli replay_png replay_float32
    replay_sequence_json replay_gt_json replay_mesh_obj replay_mesh_ply replay_mesh_stl)
# Leak checking is off: PoCL and Mesa keep allocations until exit. Memory errors and UB stop the run.
set(ENV{ASAN_OPTIONS} "detect_leaks=0:abort_on_error=1")
set(ENV{UBSAN_OPTIONS} "print_stacktrace=1:halt_on_error=1")
set(ENV{POCL_CACHE_DIR} ${WORK_DIR}/pocl-cache)
run(${WORK_DIR}/tests/depthtrack_sanitized_tests)
foreach(name png float32 sequence_json gt_json mesh_obj mesh_ply mesh_stl)
  run(${WORK_DIR}/fuzz/replay_${name} ${SOURCE_DIR}/fuzz/corpus/${name})
endforeach()
