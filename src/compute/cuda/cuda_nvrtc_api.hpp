#pragma once
// NVRTC (CUDA's run-time compiler) as a table of function pointers, opened at run time like the
// driver (see cuda_driver_api.hpp): it compiles cl/ kernels to PTX or cubin and needs no GPU.
#include <nvrtc.h>

#include <string>

namespace depthtrack::compute::cuda {

// Every NVRTC function the backend uses; the library is unusable without one of them.
// clang-format off
#define DT_NVRTC_FUNCTIONS(X)                                                                      \
  X(nvrtcVersion) X(nvrtcGetErrorString) X(nvrtcGetNumSupportedArchs) X(nvrtcGetSupportedArchs)    \
  X(nvrtcCreateProgram) X(nvrtcDestroyProgram) X(nvrtcCompileProgram)                              \
  X(nvrtcGetProgramLogSize) X(nvrtcGetProgramLog) X(nvrtcGetPTXSize) X(nvrtcGetPTX)
// clang-format on
// Machine code straight from NVRTC (CUDA 11.1+); without it the driver compiles PTX.
#define DT_NVRTC_OPTIONAL_FUNCTIONS(X) X(nvrtcGetCUBINSize) X(nvrtcGetCUBIN)

struct NvrtcApi {
#define DT_NVRTC_DECLARE(f) decltype(&::f) f = nullptr;
  DT_NVRTC_FUNCTIONS(DT_NVRTC_DECLARE)
  DT_NVRTC_OPTIONAL_FUNCTIONS(DT_NVRTC_DECLARE)
#undef DT_NVRTC_DECLARE
  std::string library;  // the file it came from, e.g. "libnvrtc.so.13"
  int major = 0, minor = 0;
};

// Loaded once (thread-safe) from libnvrtc.so.13, .12, libnvrtc.so or /usr/local/cuda/lib64;
// nullptr when none loads, and then nvrtc_failure() says why.
const NvrtcApi* nvrtc_api();
const std::string& nvrtc_failure();
// The table, or BackendError "NVRTC is unavailable: <why>".
const NvrtcApi& require_nvrtc();

}  // namespace depthtrack::compute::cuda
