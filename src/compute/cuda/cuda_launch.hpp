#pragma once
// OpenCL's nd-range in CUDA's terms: global / local blocks of local threads per dimension, checked
// against the device's and the kernel's limits before the driver sees it.
#include <string>

#include "compute/queue.hpp"

namespace depthtrack::compute::cuda {

struct LaunchLimits {
  size_t max_threads = 0;           // per block: the smaller of the device's and the kernel's
  size_t max_block[3] = {0, 0, 0};  // threads per block, per dimension
  size_t max_grid[3] = {0, 0, 0};   // blocks per dimension
};

struct LaunchShape {
  unsigned grid[3] = {1, 1, 1};
  unsigned block[3] = {1, 1, 1};
};

// The grid and block for `range`. InputError for a malformed range (dimensions outside 1..3, a zero
// size, a global size the local size does not divide); BackendError when the block or grid exceeds
// what the device or kernel allows. `kernel` and `where` name the launch in messages.
LaunchShape launch_shape(const NdRange& range, const LaunchLimits& limits, const std::string& kernel,
                         const std::string& where);

}  // namespace depthtrack::compute::cuda
