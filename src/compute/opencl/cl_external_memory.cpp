#include "compute/opencl/cl_external_memory.hpp"

#include <CL/cl_ext.h>
#include <dlfcn.h>
#include <unistd.h>

#include <depthtrack/error.hpp>
#include <string>

#include "compute/opencl/cl_errors.hpp"
#include "compute/opencl/cl_memory.hpp"

namespace depthtrack::compute::opencl {

namespace {
// OpenCL 3.0's clCreateBufferWithProperties, found in the ICD loader at run time: the headers are
// used at version 1.2, the version every platform here offers.
using CreateBufferWithProperties = cl_mem (*)(cl_context, const cl_ulong*, cl_mem_flags, size_t, void*, cl_int*);
using EnqueueExternal = cl_int (*)(cl_command_queue, cl_uint, const cl_mem*, cl_uint, const cl_event*, cl_event*);

cl_platform_id platform_of(cl_device_id device) {
  cl_platform_id platform = nullptr;
  clGetDeviceInfo(device, CL_DEVICE_PLATFORM, sizeof platform, &platform, nullptr);
  return platform;
}

// The queue's OpenCL objects, from its native handles; InputError for a queue of another API.
struct ClSide {
  cl_context context;
  cl_device_id device;
  cl_command_queue queue;
};
ClSide cl_side(const Queue& queue, const char* use) {
  const NativeHandles native = queue.native_handles();
  if (!native.cl_context)
    throw InputError(std::string(use) + " on " + queue.info().name + ": the queue is not an OpenCL queue");
  return {static_cast<cl_context>(native.cl_context), static_cast<cl_device_id>(native.cl_device),
          static_cast<cl_command_queue>(native.cl_queue)};
}

void enqueue_external(Queue& queue, const DeviceMemory& memory, const char* name) {
  const ClSide cl = cl_side(queue, name);
  auto f = reinterpret_cast<EnqueueExternal>(clGetExtensionFunctionAddressForPlatform(platform_of(cl.device), name));
  if (!f) throw BackendError(std::string(name) + " is not offered by the platform of " + queue.info().name);
  const cl_mem buffer = cl_buffer(memory, name);
  check(f(cl.queue, 1, &buffer, 0, nullptr, nullptr), name, queue.info().name);
}
}  // namespace

std::unique_ptr<DeviceMemory> import_opaque_fd(Queue& queue, int fd, size_t bytes) {
  const ClSide cl = cl_side(queue, "clCreateBufferWithProperties");
  auto create = reinterpret_cast<CreateBufferWithProperties>(dlsym(RTLD_DEFAULT, "clCreateBufferWithProperties"));
  if (!create) throw BackendError("the OpenCL ICD loader lacks clCreateBufferWithProperties (OpenCL 3.0)");
  const int duplicate = dup(fd);
  if (duplicate < 0) throw BackendError("dup of the exported memory's fd failed");
  const cl_ulong properties[] = {
      CL_EXTERNAL_MEMORY_HANDLE_OPAQUE_FD_KHR, static_cast<cl_ulong>(duplicate), CL_DEVICE_HANDLE_LIST_KHR,
      reinterpret_cast<cl_ulong>(cl.device),   CL_DEVICE_HANDLE_LIST_END_KHR,    0};
  cl_int status = CL_SUCCESS;
  MemHandle buffer(create(cl.context, properties, CL_MEM_READ_WRITE, bytes, nullptr, &status));
  if (status != CL_SUCCESS) close(duplicate);
  check(status, "clCreateBufferWithProperties (CL_EXTERNAL_MEMORY_HANDLE_OPAQUE_FD_KHR)", queue.info().name,
        std::to_string(bytes) + " bytes");
  return std::make_unique<ClMemory>(std::move(buffer), bytes);
}

void acquire_external(Queue& queue, const DeviceMemory& memory) {
  enqueue_external(queue, memory, "clEnqueueAcquireExternalMemObjectsKHR");
}

void release_external(Queue& queue, const DeviceMemory& memory) {
  enqueue_external(queue, memory, "clEnqueueReleaseExternalMemObjectsKHR");
}

}  // namespace depthtrack::compute::opencl
