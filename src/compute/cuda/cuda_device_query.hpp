#pragma once
// What one CUDA device is (DeviceInfo) and what a launch on it may ask for (LaunchLimits).
#include <string>

#include "compute/cuda/cuda_driver_api.hpp"
#include "compute/cuda/cuda_launch.hpp"
#include "compute/device_info.hpp"

namespace depthtrack::compute::cuda {

// "13.0" for the driver's 13000.
std::string format_cuda_version(int version);

int device_attribute(const DriverApi& api, CUdevice device, CUdevice_attribute attribute);
// major * 10 + minor, e.g. 90 for sm_90.
int compute_capability(const DriverApi& api, CUdevice device);

DeviceInfo query_device(const DriverApi& api, int ordinal);
LaunchLimits device_limits(const DriverApi& api, CUdevice device);

}  // namespace depthtrack::compute::cuda
