#pragma once
// Page-locked host memory that copies to the device go through, so that the stream runs them as DMA
// in order with its work and the host does not wait (a copy from pageable memory is staged by the
// driver, which may wait). One area reused by each copy: a copy first waits for the one before it
// to have left the area, which a frame's one upload has long done.
#include <cuda.h>

#include <memory>

#include "compute/cuda/cuda_context.hpp"

namespace depthtrack::compute::cuda {

class PinnedStaging {
 public:
  explicit PinnedStaging(std::shared_ptr<const Context> context);
  ~PinnedStaging();  // waits for the last copy
  PinnedStaging(const PinnedStaging&) = delete;
  PinnedStaging& operator=(const PinnedStaging&) = delete;

  // Takes `bytes` from `source` into the area, then enqueues their copy to `destination` on `stream`.
  void copy_to_device(CUdeviceptr destination, const void* source, size_t bytes, CUstream stream);

 private:
  void wait_for_last_copy();

  std::shared_ptr<const Context> context_;
  void* host_ = nullptr;
  size_t capacity_ = 0;
  CUevent copied_ = nullptr;  // recorded after each copy
  bool copying_ = false;
};

}  // namespace depthtrack::compute::cuda
