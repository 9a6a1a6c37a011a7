#pragma once
// Enumerating OpenCL platforms and devices, and describing a device as DeviceInfo.
#include <CL/cl.h>

#include <optional>
#include <utility>
#include <vector>

#include "compute/device_info.hpp"

namespace depthtrack::compute::opencl {

// Every platform the ICD loader knows; empty when there is no ICD (CL_PLATFORM_NOT_FOUND_KHR).
std::vector<cl_platform_id> platform_ids();
// Every device of a platform; empty when it has none (CL_DEVICE_NOT_FOUND).
std::vector<cl_device_id> device_ids(cl_platform_id platform);
// What the device is and offers; selector "opencl:<platform_index>.<device_index>".
DeviceInfo query_device(cl_platform_id platform, cl_device_id device, unsigned platform_index, unsigned device_index);
// The platform and device indices of an OpenCL device query_device described; none for another backend's.
std::optional<std::pair<unsigned, unsigned>> device_indices(const DeviceInfo& device);

}  // namespace depthtrack::compute::opencl
