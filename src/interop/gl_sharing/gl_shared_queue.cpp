#include "interop/gl_sharing/gl_shared_queue.hpp"

#include <CL/cl_gl.h>

#include <algorithm>
#include <depthtrack/error.hpp>
#include <vector>

#include "compute/opencl/cl_device_query.hpp"
#include "compute/opencl/cl_errors.hpp"
#include "compute/opencl/cl_queue.hpp"
#include "interop/gl_sharing/gl_sharing_choice.hpp"

namespace depthtrack::interop {

namespace {
// The devices the platform says can share `properties`' GL context (CL_DEVICES_FOR_GL_CONTEXT_KHR).
std::vector<cl_device_id> devices_for_gl_context(cl_platform_id platform,
                                                 const std::vector<cl_context_properties>& properties) {
  auto get_info = reinterpret_cast<clGetGLContextInfoKHR_fn>(
      clGetExtensionFunctionAddressForPlatform(platform, "clGetGLContextInfoKHR"));
  if (!get_info) throw BackendError("the OpenCL platform lists cl_khr_gl_sharing but has no clGetGLContextInfoKHR");
  size_t bytes = 0;
  compute::opencl::check(get_info(properties.data(), CL_DEVICES_FOR_GL_CONTEXT_KHR, 0, nullptr, &bytes),
                         "clGetGLContextInfoKHR(CL_DEVICES_FOR_GL_CONTEXT_KHR)");
  std::vector<cl_device_id> devices(bytes / sizeof(cl_device_id));
  compute::opencl::check(get_info(properties.data(), CL_DEVICES_FOR_GL_CONTEXT_KHR, bytes, devices.data(), nullptr),
                         "clGetGLContextInfoKHR(CL_DEVICES_FOR_GL_CONTEXT_KHR)");
  return devices;
}
}  // namespace

std::unique_ptr<compute::Queue> open_gl_shared_queue(const compute::DeviceInfo& device, const render::GlContext& gl) {
  const auto indices = compute::opencl::device_indices(device);
  if (!indices) throw BackendError("cl_khr_gl_sharing is OpenCL's; " + device.selector + " is not an OpenCL device");
  const auto [platform_index, device_index] = *indices;
  if (std::find(device.extensions.begin(), device.extensions.end(), "cl_khr_gl_sharing") == device.extensions.end())
    throw BackendError(device.selector + " (" + device.platform + ") does not list cl_khr_gl_sharing");
  const std::vector<cl_context_properties> shared = gl_sharing_properties(gl.native());

  const auto platforms = compute::opencl::platform_ids();
  if (platform_index >= platforms.size()) throw BackendError("no OpenCL platform " + std::to_string(platform_index));
  const auto ids = compute::opencl::device_ids(platforms[platform_index]);
  if (device_index >= ids.size()) throw BackendError("no OpenCL device " + device.selector);
  const cl_platform_id platform = platforms[platform_index];
  const cl_device_id id = ids[device_index];

  std::vector<cl_context_properties> query = {CL_CONTEXT_PLATFORM, reinterpret_cast<cl_context_properties>(platform)};
  query.insert(query.end(), shared.begin(), shared.end());
  query.push_back(0);
  const auto gl_devices = devices_for_gl_context(platform, query);
  if (std::find(gl_devices.begin(), gl_devices.end(), id) == gl_devices.end())
    throw BackendError("the GL context (" + gl.describe() + ") is not on " + device.selector + " " + device.name +
                       ": clGetGLContextInfoKHR names " + std::to_string(gl_devices.size()) + " other device(s)");
  return std::make_unique<compute::opencl::ClQueue>(
      platform, id, compute::opencl::query_device(platform, id, platform_index, device_index), shared);
}

}  // namespace depthtrack::interop
