#include "compute/cuda/cuda_backend.hpp"

#include <depthtrack/error.hpp>

#include "compute/cuda/cuda_device_query.hpp"
#include "compute/cuda/cuda_errors.hpp"
#include "compute/cuda/cuda_queue.hpp"

namespace depthtrack::compute::cuda {
namespace {

struct Enumeration {
  std::vector<DeviceInfo> devices;
  std::string reason;  // why there are none (or why some are missing)
};

// Listing never throws: a machine without CUDA simply has no CUDA devices.
Enumeration enumerate() {
  Enumeration out;
  const DriverApi* api = driver_api();
  if (!api) {
    out.reason = driver_failure();
    return out;
  }
  int count = 0;
  if (const CUresult status = api->cuDeviceGetCount(&count); status != CUDA_SUCCESS) {
    out.reason = "cuDeviceGetCount failed: " + cuda_error_text(*api, status);
    return out;
  }
  if (count == 0) out.reason = "the NVIDIA driver reports no CUDA device";
  for (int ordinal = 0; ordinal < count; ++ordinal) {
    try {
      out.devices.push_back(query_device(*api, ordinal));
    } catch (const std::exception& error) {  // keep the others: their selectors stay right
      out.reason += (out.reason.empty() ? "" : "; ") + std::string(error.what());
    }
  }
  return out;
}

// Devices do not come and go while a process runs; ask the driver once.
const Enumeration& enumeration() {
  static const Enumeration instance = enumerate();
  return instance;
}

}  // namespace

std::vector<DeviceInfo> devices() {
  return enumeration().devices;
}

std::string unavailable_reason() {
  return enumeration().reason;
}

std::unique_ptr<Queue> open(unsigned ordinal) {
  const Enumeration& found = enumeration();
  if (!driver_api()) throw BackendError("CUDA is unavailable: " + found.reason);
  for (const DeviceInfo& device : found.devices)
    if (device.selector == "cuda:" + std::to_string(ordinal))
      return std::make_unique<CudaQueue>(static_cast<int>(ordinal));
  std::string available;
  for (const DeviceInfo& device : found.devices)
    available += (available.empty() ? "" : ", ") + device.selector + " (" + device.name + ")";
  throw InputError("there is no CUDA device cuda:" + std::to_string(ordinal) + "; CUDA devices: " +
                   (available.empty() ? "none" : available) + (found.reason.empty() ? "" : " (" + found.reason + ")"));
}

}  // namespace depthtrack::compute::cuda
