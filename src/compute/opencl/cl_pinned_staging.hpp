#pragma once
// Host memory the driver can copy from and to by DMA, for the enqueued transfers: a buffer made with
// CL_MEM_ALLOC_HOST_PTR and mapped for the area's lifetime (the pinned-memory path of NVIDIA's OpenCL
// guide; other drivers take it as host memory). A transfer from or to ordinary host memory is staged
// by the driver first: on NVIDIA's OpenCL (H100) enqueueing a 19 KB non-blocking
// write cost the host about 55 us and a 224-byte read 45 us that way. One area reused by each transfer, as
// cuda::PinnedStaging: a transfer first waits for the one before it to be done with the area, unless
// the queue knows its stream passed a later point. A queue keeps one for writes and one for reads.
#include <CL/cl.h>

#include <string>

#include "compute/opencl/cl_handle.hpp"

namespace depthtrack::compute::opencl {

class PinnedStaging {
 public:
  PinnedStaging(cl_context context, cl_command_queue queue, std::string device_name);
  ~PinnedStaging();  // waits for the last transfer, then unmaps
  PinnedStaging(const PinnedStaging&) = delete;
  PinnedStaging& operator=(const PinnedStaging&) = delete;

  // Takes `bytes` from `source` into the area, then enqueues their write to `destination` at `offset`.
  void copy_to_device(cl_mem destination, size_t offset, const void* source, size_t bytes);
  // Enqueues a read of `bytes` from `source` at `offset` into the area; deliver() hands them to `destination`.
  void copy_to_host(void* destination, cl_mem source, size_t offset, size_t bytes);
  // Waits for the last copy_to_host and copies its bytes to their destination (none pending: nothing).
  void deliver();
  // Whether a transfer may still be under way, and the queue's word that it is not (its in-order
  // queue reached a later point), so that the next transfer skips the wait on its event (26 us a
  // frame on NVIDIA's OpenCL, where waiting even on a finished event costs that much).
  bool copy_pending() const { return copying_; }
  void copy_known_done() { copying_ = false; }

 private:
  void wait_for_last_copy();
  void reserve(size_t bytes);  // with no transfer pending
  void release_area();

  cl_context context_;
  cl_command_queue queue_;
  std::string device_;
  MemHandle area_;
  void* host_ = nullptr;  // area_ mapped
  size_t capacity_ = 0;
  EventHandle copied_;  // the last transfer's
  bool copying_ = false;
  void* destination_ = nullptr;  // copy_to_host's, until deliver()
  size_t pending_bytes_ = 0;
};

}  // namespace depthtrack::compute::opencl
