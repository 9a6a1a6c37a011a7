#pragma once
// Driver and NVRTC status codes as depthtrack::BackendError: the call, the symbolic name and the
// number, and where it happened ("cuMemAlloc failed: CUDA_ERROR_OUT_OF_MEMORY (2) on NVIDIA H100
// 80GB HBM3 (cuda:0): out of memory").
#include <string>

#include "compute/cuda/cuda_driver_api.hpp"
#include "compute/cuda/cuda_nvrtc_api.hpp"

namespace depthtrack::compute::cuda {

// "CUDA_ERROR_OUT_OF_MEMORY (2)", from the driver's own names.
std::string cuda_error_text(const DriverApi& api, CUresult status);
// Throws BackendError unless status is CUDA_SUCCESS; where names the device (may be empty).
void check(CUresult status, const char* call, const std::string& where);

// "NVRTC_ERROR_COMPILATION (6)".
std::string nvrtc_error_text(const NvrtcApi& api, nvrtcResult status);
void check_nvrtc(const NvrtcApi& api, nvrtcResult status, const char* call);

}  // namespace depthtrack::compute::cuda
