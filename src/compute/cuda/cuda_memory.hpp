#pragma once
// A device allocation (cuMemAlloc), freed with its context current when destroyed.
#include <memory>

#include "compute/cuda/cuda_context.hpp"
#include "compute/queue.hpp"

namespace depthtrack::compute::cuda {

class CudaMemory final : public DeviceMemory {
 public:
  CudaMemory(std::shared_ptr<const Context> context, size_t bytes);
  ~CudaMemory() override;
  CudaMemory(const CudaMemory&) = delete;
  CudaMemory& operator=(const CudaMemory&) = delete;

  size_t bytes() const override { return bytes_; }
  CUdeviceptr pointer() const { return pointer_; }
  const Context& context() const { return *context_; }

 private:
  std::shared_ptr<const Context> context_;
  size_t bytes_;
  CUdeviceptr pointer_ = 0;
};

// `memory` as CUDA memory of `context`; InputError when it belongs to another backend or device.
const CudaMemory& cuda_memory(const DeviceMemory& memory, const Context& context, const std::string& use);
// The same for the device a queue's native handles name (NativeHandles::cu_device); `where` names it.
const CudaMemory& cuda_memory(const DeviceMemory& memory, CUdevice device, const std::string& where,
                              const std::string& use);

}  // namespace depthtrack::compute::cuda
