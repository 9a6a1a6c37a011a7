#pragma once
// A cl_kernel as Kernel: an argument goes to clSetKernelArg when it differs from what the kernel holds.
#include <string>
#include <vector>

#include "compute/opencl/cl_handle.hpp"
#include "compute/queue.hpp"

namespace depthtrack::compute::opencl {

class ClKernel final : public Kernel {
 public:
  ClKernel(KernelHandle kernel, std::string name, std::string device)
      : kernel_(std::move(kernel)), name_(std::move(name)), device_(std::move(device)) {}
  using Kernel::set_arg;
  const std::string& name() const override { return name_; }
  void set_arg(unsigned index, const DeviceMemory& memory) override;
  void set_arg_bytes(unsigned index, const void* value, size_t size) override;
  cl_kernel get() const { return kernel_.get(); }

 private:
  std::string describe_arg(unsigned index) const;
  // Whether argument index already holds these bytes; if not, they are remembered as what it will hold.
  bool holds(unsigned index, const void* value, size_t size);

  KernelHandle kernel_;
  std::string name_;
  std::string device_;
  // What each argument was last set to (a buffer: its ClMemory::serial; empty: not set). A launch sets
  // every argument and most are the same frame after frame, while each clSetKernelArg costs the host
  // on NVIDIA's OpenCL; the kernel keeps a set value until it is set again (OpenCL 1.2, 5.9.2).
  std::vector<std::vector<unsigned char>> held_;
};

}  // namespace depthtrack::compute::opencl
