#include "compute/cuda/cuda_errors.hpp"

#include <depthtrack/error.hpp>

namespace depthtrack::compute::cuda {

std::string cuda_error_text(const DriverApi& api, CUresult status) {
  const char* name = nullptr;
  // cuGetErrorName fails for codes the driver does not know (newer headers, corrupt values).
  if (api.cuGetErrorName(status, &name) != CUDA_SUCCESS || !name) name = "CUDA_ERROR_UNKNOWN_CODE";
  return std::string(name) + " (" + std::to_string(static_cast<int>(status)) + ")";
}

void check(CUresult status, const char* call, const std::string& where) {
  if (status == CUDA_SUCCESS) return;
  // Only reachable after the driver loaded: every status comes from one of its calls.
  const DriverApi& api = require_driver();
  std::string message = std::string(call) + " failed: " + cuda_error_text(api, status);
  if (!where.empty()) message += " on " + where;
  const char* description = nullptr;
  if (api.cuGetErrorString(status, &description) == CUDA_SUCCESS && description)
    message += std::string(": ") + description;
  throw BackendError(message);
}

std::string nvrtc_error_text(const NvrtcApi& api, nvrtcResult status) {
  const char* name = api.nvrtcGetErrorString(status);
  return std::string(name ? name : "NVRTC_ERROR_UNKNOWN_CODE") + " (" + std::to_string(static_cast<int>(status)) + ")";
}

void check_nvrtc(const NvrtcApi& api, nvrtcResult status, const char* call) {
  if (status != NVRTC_SUCCESS) throw BackendError(std::string(call) + " failed: " + nvrtc_error_text(api, status));
}

}  // namespace depthtrack::compute::cuda
