#pragma once
// Entry points of the CUDA backend: the driver API and NVRTC, both opened at run time (dlopen),
// so a build with the backend still loads where no NVIDIA driver is installed.
#include <memory>
#include <string>
#include <vector>

#include "compute/queue.hpp"

namespace depthtrack::compute::cuda {

// Every CUDA device; selectors "cuda:<n>". Empty (not an error) when libcuda.so.1 is absent or
// reports no device; why is kept for messages (unavailable_reason()).
std::vector<DeviceInfo> devices();
std::string unavailable_reason();
std::unique_ptr<Queue> open(unsigned ordinal);

}  // namespace depthtrack::compute::cuda
