#include "compute/opencl/cl_kernel.hpp"

#include <depthtrack/error.hpp>

#include "compute/opencl/cl_errors.hpp"
#include "compute/opencl/cl_memory.hpp"

namespace depthtrack::compute::opencl {

std::string ClKernel::describe_arg(unsigned index) const {
  std::string text = "argument " + std::to_string(index) + " of kernel '" + name_ + "'";
  cl_uint count = 0;
  if (clGetKernelInfo(kernel_.get(), CL_KERNEL_NUM_ARGS, sizeof count, &count, nullptr) == CL_SUCCESS)
    text += " (it takes " + std::to_string(count) + (count == 1 ? " argument)" : " arguments)");
  return text;
}

void ClKernel::set_arg(unsigned index, const DeviceMemory& memory) {
  const auto* cl = dynamic_cast<const ClMemory*>(&memory);
  if (!cl) throw InputError(describe_arg(index) + ": the device memory was not allocated by an OpenCL queue");
  const cl_mem buffer = cl->get();
  const cl_int status = clSetKernelArg(kernel_.get(), index, sizeof buffer, &buffer);
  if (status != CL_SUCCESS) check(status, "clSetKernelArg", device_, describe_arg(index));
}

void ClKernel::set_arg_bytes(unsigned index, const void* value, size_t size) {
  const cl_int status = clSetKernelArg(kernel_.get(), index, size, value);
  if (status != CL_SUCCESS)
    check(status, "clSetKernelArg", device_, describe_arg(index) + ", a value of " + std::to_string(size) + " bytes");
}

}  // namespace depthtrack::compute::opencl
