#pragma once
// One device's primary context, shared (std::shared_ptr) by the queue and everything made from it,
// memory, programs, kernels and events, so that it is released only after the last of them.
// The primary context is the one the CUDA runtime and CUDA-GL interop use too.
#include <atomic>
#include <memory>
#include <string>

#include "compute/cuda/cuda_driver_api.hpp"
#include "compute/cuda/cuda_launch.hpp"
#include "compute/device_info.hpp"

namespace depthtrack::compute::cuda {

class Context {
 public:
  // Retains device `ordinal`'s primary context; BackendError when it cannot.
  explicit Context(int ordinal);
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  const DriverApi& api() const { return api_; }
  const DeviceInfo& info() const { return info_; }
  CUdevice device() const { return device_; }
  CUcontext get() const { return context_; }
  int compute_capability() const { return compute_capability_; }
  const LaunchLimits& limits() const { return limits_; }
  // "NVIDIA H100 80GB HBM3 (cuda:0)", for messages.
  const std::string& where() const { return where_; }

  // Makes this context current on the calling thread. Every entry point calls it first, so a
  // queue works from whichever thread uses it, next to other code that switches contexts.
  void make_current() const;
  // The same without throwing, for destructors.
  bool try_make_current() const noexcept { return api_.cuCtxSetCurrent(context_) == CUDA_SUCCESS; }
  // check() naming this device.
  void check(CUresult status, const char* call) const;
  // The next queue's rank in this context (0 for the first made): its stream's priority
  // (compute/cuda/cuda_stream.hpp).
  unsigned take_queue_rank() const { return queues_made_.fetch_add(1); }

 private:
  const DriverApi& api_;
  CUdevice device_ = 0;
  CUcontext context_ = nullptr;
  DeviceInfo info_;
  int compute_capability_ = 0;
  LaunchLimits limits_;
  std::string where_;
  mutable std::atomic<unsigned> queues_made_{0};
};

}  // namespace depthtrack::compute::cuda
