# A sketch of a new compute backend, to show what adding one takes: this folder and one line
# (tests/CMakeLists.txt: depthtrack_add_backend(${CMAKE_CURRENT_SOURCE_DIR}/sketch_backend TO depthtrack_tests)).
# A library backend has the same three files in src/compute/<name>/ and its line in src/CMakeLists.txt; it would
# also have an option and find_package here, as src/compute/opencl/backend.cmake does. The sketch needs neither.
message(STATUS "depthtrack: sketch backend (tests only)")
depthtrack_compute_backend(sketch Sketch ON)
