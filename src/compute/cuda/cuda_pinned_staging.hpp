#pragma once
// Page-locked host memory that enqueued copies go through, so that the stream runs them as DMA in
// order with its work and the host does not wait (a copy from or to pageable memory is staged by the
// driver, which may wait). One area reused by each copy: a copy first waits for the one before it to
// be done with the area, which a frame's one upload has long been. A queue keeps one for uploads and
// one for reads, each used in one direction.
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
  // Enqueues a copy of `bytes` from `source` into the area on `stream`; deliver() hands them to
  // `destination`.
  void copy_to_host(void* destination, CUdeviceptr source, size_t bytes, CUstream stream);
  // Waits for the last copy_to_host and copies its bytes to their destination (none pending: nothing).
  void deliver();
  // Whether a copy may still be under way, and the queue's word that it is not (its stream reached a
  // later point), so that the next copy skips the wait on its event (a few microseconds a frame).
  bool copy_pending() const { return copying_; }
  void copy_known_done() { copying_ = false; }

 private:
  void wait_for_last_copy();
  void reserve(size_t bytes);  // with no copy pending

  std::shared_ptr<const Context> context_;
  void* host_ = nullptr;
  size_t capacity_ = 0;
  CUevent copied_ = nullptr;  // recorded after each copy
  bool copying_ = false;
  void* destination_ = nullptr;  // copy_to_host's, until deliver()
  size_t pending_bytes_ = 0;
};

}  // namespace depthtrack::compute::cuda
