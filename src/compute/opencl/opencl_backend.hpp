#pragma once
// Entry points of the OpenCL backend (through the ICD loader: PoCL, NVIDIA, AMD, Intel).
#include <memory>
#include <string>
#include <vector>

#include "compute/queue.hpp"

namespace depthtrack::compute::opencl {

// Every device of every platform; selectors "opencl:<platform>.<device>". Empty (not an error)
// when there is no ICD or no platform.
std::vector<DeviceInfo> devices();
// The device "opencl:<platform>.<device>" indices name.
std::unique_ptr<Queue> open(unsigned platform, unsigned device);

}  // namespace depthtrack::compute::opencl
