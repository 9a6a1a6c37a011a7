# ctest driver: install the built project into a scratch prefix, run the installed command with no folder
# of this build on LD_LIBRARY_PATH (its RUNPATH finds the library), then configure, build and run the consumer against it.
# Inputs: SOURCE_DIR, BUILD_DIR, WORK_DIR; STATIC=ON first builds the library and the command static in
# WORK_DIR/static (GENERATOR, CXX_COMPILER, LAUNCHER, WERROR, WITH_CUDA as in the outer build, so that a
# compiler cache finds the outer build's objects), so the package's static branch is what the consumer meets.
# SEARCH_PATHS: a file setting the outer build's OUTER_PREFIX_PATH, OUTER_LIBRARY_PATH and OUTER_INCLUDE_PATH
# (tests/CMakeLists.txt), handed to both configures so that they find the dependencies where it did.
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}")
  endif()
  message("${out}")
  set(output "${out}" PARENT_SCOPE)
endfunction()
file(REMOVE_RECURSE ${WORK_DIR}/prefix ${WORK_DIR}/build)
# The outer build's search paths as initial caches (a list in a -D argument would not survive run()'s
# argument list), the scratch prefix first for the consumer.
include(${SEARCH_PATHS})
function(write_search_paths file prefix_path)
  file(WRITE ${file} "set(CMAKE_PREFIX_PATH \"${prefix_path}\" CACHE STRING \"\")\n"
                     "set(CMAKE_LIBRARY_PATH \"${OUTER_LIBRARY_PATH}\" CACHE STRING \"\")\n"
                     "set(CMAKE_INCLUDE_PATH \"${OUTER_INCLUDE_PATH}\" CACHE STRING \"\")\n")
endfunction()
write_search_paths(${WORK_DIR}/search-paths.cmake "${OUTER_PREFIX_PATH}")
set(consumer_prefix_path ${WORK_DIR}/prefix ${OUTER_PREFIX_PATH})  # no empty entry when the outer had none
write_search_paths(${WORK_DIR}/consumer-search-paths.cmake "${consumer_prefix_path}")
if(STATIC)
  set(launcher "")
  if(LAUNCHER)
    set(launcher -DCMAKE_CXX_COMPILER_LAUNCHER=${LAUNCHER})
  endif()
  # The tree is kept between runs, so a later run rebuilds only what changed.
  run(${CMAKE_COMMAND} -C ${WORK_DIR}/search-paths.cmake -S ${SOURCE_DIR} -B ${WORK_DIR}/static -G ${GENERATOR}
      -DCMAKE_CXX_COMPILER=${CXX_COMPILER}
      ${launcher} -DCMAKE_BUILD_TYPE=Release -DBUILD_SHARED_LIBS=OFF -DDEPTHTRACK_BUILD_TESTS=OFF
      -DDEPTHTRACK_BUILD_BENCH=OFF -DDEPTHTRACK_PYTHON=OFF -DDEPTHTRACK_WERROR=${WERROR} -DDEPTHTRACK_WITH_CUDA=${WITH_CUDA})
  run(${CMAKE_COMMAND} --build ${WORK_DIR}/static -j2 --target depthtrack depthtrack_cli)
  set(BUILD_DIR ${WORK_DIR}/static)
endif()
run(${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${WORK_DIR}/prefix)
if(STATIC AND NOT EXISTS ${WORK_DIR}/prefix/lib/libdepthtrack.a)
  message(FATAL_ERROR "the static build installed no lib/libdepthtrack.a")
endif()
# The installed command must find libdepthtrack by its RUNPATH: LD_LIBRARY_PATH keeps only the folders
# outside this build and the scratch prefix (a package folder of third-party libraries stays, as on the
# GPU machine, where assimp lives in one).
string(REPLACE ":" ";" outer_library_path "$ENV{LD_LIBRARY_PATH}")
set(library_path "")
foreach(folder IN LISTS outer_library_path)
  string(FIND "${folder}" "${BUILD_DIR}" in_build)
  string(FIND "${folder}" "${WORK_DIR}" in_work)
  if(NOT folder STREQUAL "" AND NOT in_build EQUAL 0 AND NOT in_work EQUAL 0)
    list(APPEND library_path "${folder}")
  endif()
endforeach()
list(JOIN library_path ":" library_path)
if(library_path STREQUAL "")
  set(library_env --unset=LD_LIBRARY_PATH)
else()
  set(library_env "LD_LIBRARY_PATH=${library_path}")
endif()
run(${CMAKE_COMMAND} -E env ${library_env} ${WORK_DIR}/prefix/bin/depthtrack info)
if(NOT output MATCHES "OpenCL: [0-9]+ device" OR NOT output MATCHES "OpenGL \\(pose atlas\\):")
  message(FATAL_ERROR "the installed `depthtrack info` printed no device list:\n${output}")
endif()
run(${CMAKE_COMMAND} -C ${WORK_DIR}/consumer-search-paths.cmake -S ${SOURCE_DIR}/tests/consumer -B ${WORK_DIR}/build
    -G Ninja -DCMAKE_BUILD_TYPE=Release)
run(${CMAKE_COMMAND} --build ${WORK_DIR}/build)
run(${WORK_DIR}/build/consumer)
