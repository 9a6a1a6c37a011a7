#pragma once
// A cl_kernel as Kernel: arguments go straight to clSetKernelArg.
#include <string>

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

  KernelHandle kernel_;
  std::string name_;
  std::string device_;
};

}  // namespace depthtrack::compute::opencl
