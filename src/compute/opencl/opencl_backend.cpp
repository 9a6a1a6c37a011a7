#include "compute/opencl/opencl_backend.hpp"

#include <cstdio>
#include <depthtrack/error.hpp>

#include "compute/opencl/cl_device_query.hpp"
#include "compute/opencl/cl_queue.hpp"

namespace depthtrack::compute::opencl {

std::vector<DeviceInfo> devices() {
  std::vector<DeviceInfo> found;
  const auto platforms = platform_ids();
  for (unsigned p = 0; p < platforms.size(); ++p) {
    // A broken platform or device is skipped with a note rather than hiding every other device.
    try {
      const auto ids = device_ids(platforms[p]);
      for (unsigned d = 0; d < ids.size(); ++d) {
        try {
          found.push_back(query_device(platforms[p], ids[d], p, d));
        } catch (const BackendError& e) {
          std::fprintf(stderr, "depthtrack: note: skipping OpenCL device %u.%u: %s\n", p, d, e.what());
        }
      }
    } catch (const BackendError& e) {
      std::fprintf(stderr, "depthtrack: note: skipping OpenCL platform %u: %s\n", p, e.what());
    }
  }
  return found;
}

std::unique_ptr<Queue> open(unsigned platform, unsigned device) {
  const auto platforms = platform_ids();
  const std::string selector = "opencl:" + std::to_string(platform) + "." + std::to_string(device);
  if (platform >= platforms.size())
    throw InputError("no OpenCL device " + selector + ": there are " + std::to_string(platforms.size()) + " platforms");
  const auto ids = device_ids(platforms[platform]);
  if (device >= ids.size())
    throw InputError("no OpenCL device " + selector + ": platform " + std::to_string(platform) + " has " +
                     std::to_string(ids.size()) + " devices");
  return std::make_unique<ClQueue>(platforms[platform], ids[device],
                                   query_device(platforms[platform], ids[device], platform, device));
}

}  // namespace depthtrack::compute::opencl
