#pragma once
// The event of one launch: a pair of CUDA events recorded on the stream around it, so that
// elapsed_ms() is the device's own time for the work between them.
#include <memory>

#include "compute/cuda/cuda_context.hpp"
#include "compute/queue.hpp"

namespace depthtrack::compute::cuda {

class CudaEvent final : public Event {
 public:
  explicit CudaEvent(std::shared_ptr<const Context> context);
  ~CudaEvent() override;
  CudaEvent(const CudaEvent&) = delete;
  CudaEvent& operator=(const CudaEvent&) = delete;

  void record_start(CUstream stream);
  void record_end(CUstream stream);
  // The two CUDA events, for a graph's event-record nodes (compute/cuda/cuda_launch_graph.hpp).
  CUevent start_handle() const { return start_; }
  CUevent end_handle() const { return end_; }
  void wait() override;
  double elapsed_ms() override;
  std::optional<double> elapsed_since_ms(Event& earlier) override;

 private:
  std::shared_ptr<const Context> context_;
  CUevent start_ = nullptr;
  CUevent end_ = nullptr;
};

}  // namespace depthtrack::compute::cuda
