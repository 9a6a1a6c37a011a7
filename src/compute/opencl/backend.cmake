# The OpenCL backend (src/CMakeLists.txt: depthtrack_add_backend(opencl)): its option, its headers, its entry.
option(DEPTHTRACK_WITH_OPENCL "Build the OpenCL backend" ON)
if(DEPTHTRACK_WITH_OPENCL)
  find_package(OpenCL REQUIRED GLOBAL)
  # The include path of the OpenCL API as a target, for the layers (and tests) that may use it.
  add_library(dt_opencl_headers INTERFACE)
  target_link_libraries(dt_opencl_headers INTERFACE OpenCL::OpenCL)
  target_compile_definitions(dt_opencl_headers INTERFACE CL_TARGET_OPENCL_VERSION=120)
endif()
message(STATUS "depthtrack: OpenCL backend ${DEPTHTRACK_WITH_OPENCL}")
depthtrack_compute_backend(opencl OpenCL "${DEPTHTRACK_WITH_OPENCL}" DEPENDS dt_opencl_headers LINK OpenCL::OpenCL
                           PACKAGE OpenCL)
