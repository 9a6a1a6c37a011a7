# ctest driver: cmake --install into a scratch prefix, then import depthtrack from there alone and
# track a frame. Inputs: BUILD_DIR, WORK_DIR, PYTHON, SITE (the package's folder under the prefix).
file(REMOVE_RECURSE ${WORK_DIR})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${WORK_DIR}/prefix
                RESULT_VARIABLE rc OUTPUT_QUIET ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cmake --install failed (${rc}): ${err}")
endif()
set(script "import depthtrack, numpy as np, sys
assert depthtrack.__file__.startswith(sys.argv[1]), depthtrack.__file__
t = depthtrack.Tracker(depthtrack.Mesh.builtin(), depthtrack.Camera(80, 60, 66, 66, 39.5, 29.5))
pose = np.eye(4)
pose[2, 3] = 0.8
t.initialize(pose)
e = t.update(np.full((60, 80), 8000, np.uint16), 0.0, metres_per_unit=1e-4)
print('installed', depthtrack.__version__, depthtrack.__file__, e.status)")
execute_process(COMMAND ${CMAKE_COMMAND} -E env PYTHONPATH=${WORK_DIR}/prefix/${SITE} --
                        ${PYTHON} -c "${script}" ${WORK_DIR}/prefix
                WORKING_DIRECTORY ${WORK_DIR} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
message("${out}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "importing the installed package failed (${rc})")
endif()
