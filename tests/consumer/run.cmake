# ctest driver: install the built project into a scratch prefix, run the installed command without
# LD_LIBRARY_PATH (its RUNPATH finds the library), then configure, build and run the consumer against it.
# Inputs: SOURCE_DIR, BUILD_DIR, WORK_DIR; STATIC=ON first builds the library and the command static in
# WORK_DIR/static (GENERATOR, CXX_COMPILER, LAUNCHER, WERROR, WITH_CUDA as in the outer build, so that a
# compiler cache finds the outer build's objects), so the package's static branch is what the consumer meets.
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}")
  endif()
  message("${out}")
  set(output "${out}" PARENT_SCOPE)
endfunction()
file(REMOVE_RECURSE ${WORK_DIR}/prefix ${WORK_DIR}/build)
if(STATIC)
  set(launcher "")
  if(LAUNCHER)
    set(launcher -DCMAKE_CXX_COMPILER_LAUNCHER=${LAUNCHER})
  endif()
  # The tree is kept between runs, so a later run rebuilds only what changed.
  run(${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${WORK_DIR}/static -G ${GENERATOR} -DCMAKE_CXX_COMPILER=${CXX_COMPILER}
      ${launcher} -DCMAKE_BUILD_TYPE=Release -DBUILD_SHARED_LIBS=OFF -DDEPTHTRACK_BUILD_TESTS=OFF
      -DDEPTHTRACK_BUILD_BENCH=OFF -DDEPTHTRACK_PYTHON=OFF -DDEPTHTRACK_WERROR=${WERROR} -DDEPTHTRACK_WITH_CUDA=${WITH_CUDA})
  run(${CMAKE_COMMAND} --build ${WORK_DIR}/static -j2 --target depthtrack depthtrack_cli)
  set(BUILD_DIR ${WORK_DIR}/static)
endif()
run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${WORK_DIR}/prefix)
if(STATIC AND NOT EXISTS ${WORK_DIR}/prefix/lib/libdepthtrack.a)
  message(FATAL_ERROR "the static build installed no lib/libdepthtrack.a")
endif()
run(${CMAKE_COMMAND} -E env --unset=LD_LIBRARY_PATH ${WORK_DIR}/prefix/bin/depthtrack info)
if(NOT output MATCHES "OpenCL: [0-9]+ device" OR NOT output MATCHES "OpenGL \\(pose atlas\\):")
  message(FATAL_ERROR "the installed `depthtrack info` printed no device list:\n${output}")
endif()
run(${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/consumer -B ${WORK_DIR}/build -G Ninja
    -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix -DCMAKE_BUILD_TYPE=Release)
run(${CMAKE_COMMAND} --build ${WORK_DIR}/build)
run(${WORK_DIR}/build/consumer)
