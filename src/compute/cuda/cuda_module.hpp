#pragma once
// A built program: NVRTC's output loaded as a CUDA module, and kernel lookup by name.
#include <memory>
#include <string>
#include <vector>

#include "compute/cuda/cuda_context.hpp"
#include "compute/cuda/cuda_program.hpp"
#include "compute/queue.hpp"

namespace depthtrack::compute::cuda {

// One loaded module, shared by its program and kernels so that it is unloaded after the last.
class Module {
 public:
  Module(std::shared_ptr<const Context> context, const CompiledImage& image, const std::string& program);
  ~Module();
  Module(const Module&) = delete;
  Module& operator=(const Module&) = delete;

  CUmodule get() const { return module_; }
  const std::shared_ptr<const Context>& context() const { return context_; }

 private:
  std::shared_ptr<const Context> context_;
  CUmodule module_ = nullptr;
};

class CudaProgram final : public Program {
 public:
  // Throws BackendError when the driver refuses the image. from_disk: it came from the binary cache.
  CudaProgram(std::shared_ptr<const Context> context, const std::string& name, const std::string& source,
              const CompiledImage& image, bool from_disk = false);
  // BackendError listing the program's __kernel names when `name` is not one of them.
  std::unique_ptr<Kernel> kernel(const std::string& name) override;
  bool loaded_from_disk() const override { return from_disk_; }

 private:
  std::shared_ptr<const Module> module_;
  std::string name_;
  std::vector<std::string> kernel_names_;
  bool from_disk_;
};

}  // namespace depthtrack::compute::cuda
