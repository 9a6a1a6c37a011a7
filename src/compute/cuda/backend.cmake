# The CUDA backend (src/CMakeLists.txt: depthtrack_add_backend(cuda)): built whenever the toolkit is found. The
# CUDA driver and NVRTC are opened at run time (dlopen), so the library loads on machines without an NVIDIA
# driver and links nothing for it; only the toolkit's headers are needed to build.
find_package(CUDAToolkit QUIET)
option(DEPTHTRACK_WITH_CUDA "Build the CUDA backend" ${CUDAToolkit_FOUND})
if(DEPTHTRACK_WITH_CUDA AND NOT CUDAToolkit_FOUND)
  message(FATAL_ERROR "DEPTHTRACK_WITH_CUDA is ON but no CUDA toolkit was found")
endif()
if(DEPTHTRACK_WITH_CUDA)
  add_library(dt_cuda_headers INTERFACE)
  target_include_directories(dt_cuda_headers INTERFACE ${CUDAToolkit_INCLUDE_DIRS})
endif()
message(STATUS "depthtrack: CUDA backend ${DEPTHTRACK_WITH_CUDA}")
depthtrack_compute_backend(cuda CUDA "${DEPTHTRACK_WITH_CUDA}" DEPENDS dt_cuda_headers)
set(DEPTHTRACK_CUDA_EXTRA_OPTIONS "" CACHE STRING "NVRTC options appended to the fixed ones (space-separated; for experiments)")
if(DEPTHTRACK_WITH_CUDA AND DEPTHTRACK_CUDA_EXTRA_OPTIONS)
  target_compile_definitions(dt_compute_cuda PRIVATE "DEPTHTRACK_CUDA_EXTRA_OPTIONS=\"${DEPTHTRACK_CUDA_EXTRA_OPTIONS}\"")
endif()
