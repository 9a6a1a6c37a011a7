#pragma once
// A cl_mem buffer as DeviceMemory.
#include <depthtrack/error.hpp>
#include <string>

#include "compute/opencl/cl_handle.hpp"
#include "compute/queue.hpp"

namespace depthtrack::compute::opencl {

class ClMemory final : public DeviceMemory {
 public:
  ClMemory(MemHandle buffer, size_t bytes) : buffer_(std::move(buffer)), bytes_(bytes) {}
  size_t bytes() const override { return bytes_; }
  cl_mem get() const { return buffer_.get(); }

 private:
  MemHandle buffer_;
  size_t bytes_;
};

// The cl_mem behind memory; InputError when it came from another backend's queue.
inline cl_mem cl_buffer(const DeviceMemory& memory, const char* use) {
  const auto* cl = dynamic_cast<const ClMemory*>(&memory);
  if (!cl) throw InputError(std::string(use) + ": the device memory was not allocated by an OpenCL queue");
  return cl->get();
}

}  // namespace depthtrack::compute::opencl
