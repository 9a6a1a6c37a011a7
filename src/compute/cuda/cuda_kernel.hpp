#pragma once
// A kernel of a loaded module and the arguments set on it so far, kept as bytes per index (a
// CUdeviceptr for memory) until a launch hands cuLaunchKernel a pointer to each.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "compute/cuda/cuda_launch.hpp"
#include "compute/cuda/cuda_module.hpp"
#include "compute/queue.hpp"

namespace depthtrack::compute::cuda {

class CudaKernel final : public Kernel {
 public:
  CudaKernel(std::shared_ptr<const Module> module, CUfunction function, std::string name);

  const std::string& name() const override { return name_; }
  using Kernel::set_arg;
  void set_arg(unsigned index, const DeviceMemory& memory) override;
  void set_arg_bytes(unsigned index, const void* value, size_t size) override;

  const Context& context() const { return *module_->context(); }
  CUfunction function() const { return function_; }
  // The device's limits, narrowed to the threads per block this kernel's registers allow.
  LaunchLimits limits() const;
  // Pointers to every argument, 0 to the last; InputError naming the first one never set.
  std::vector<void*> argument_pointers();
  // A copy of every argument's bytes, appended to `bytes`, each at an offset (pushed to `offsets`) aligned
  // for any parameter type; InputError as argument_pointers() for one never set.
  void copy_arguments(std::vector<unsigned char>& bytes, std::vector<size_t>& offsets) const;

 private:
  std::string describe_arg(unsigned index) const;
  std::shared_ptr<const Module> module_;
  CUfunction function_;
  std::string name_;
  size_t max_threads_ = 0;
  // The size of each parameter, when the driver can say (cuFuncGetParamInfo, CUDA 12.4+).
  std::optional<std::vector<size_t>> parameter_sizes_;
  std::vector<std::optional<std::vector<unsigned char>>> arguments_;
};

}  // namespace depthtrack::compute::cuda
