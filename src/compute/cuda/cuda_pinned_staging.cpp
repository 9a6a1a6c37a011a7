#include "compute/cuda/cuda_pinned_staging.hpp"

#include <cstring>

namespace depthtrack::compute::cuda {

PinnedStaging::PinnedStaging(std::shared_ptr<const Context> context) : context_(std::move(context)) {
  context_->make_current();
  // Ordering only: no timing records.
  context_->check(context_->api().cuEventCreate(&copied_, CU_EVENT_DISABLE_TIMING), "cuEventCreate");
}

PinnedStaging::~PinnedStaging() {
  if (!context_->try_make_current()) return;
  if (copying_) context_->api().cuEventSynchronize(copied_);  // the area must outlive the copy
  if (host_) context_->api().cuMemFreeHost(host_);
  context_->api().cuEventDestroy(copied_);
}

void PinnedStaging::wait_for_last_copy() {
  if (!copying_) return;
  context_->check(context_->api().cuEventSynchronize(copied_), "cuEventSynchronize");
  copying_ = false;
}

void PinnedStaging::reserve(size_t bytes) {
  if (bytes <= capacity_) return;
  if (host_) context_->check(context_->api().cuMemFreeHost(host_), "cuMemFreeHost");
  host_ = nullptr;
  capacity_ = 0;
  context_->check(context_->api().cuMemAllocHost(&host_, bytes), "cuMemAllocHost");
  capacity_ = bytes;
}

void PinnedStaging::copy_to_device(CUdeviceptr destination, const void* source, size_t bytes, CUstream stream) {
  wait_for_last_copy();
  reserve(bytes);
  std::memcpy(host_, source, bytes);
  context_->check(context_->api().cuMemcpyHtoDAsync(destination, host_, bytes, stream), "cuMemcpyHtoDAsync");
  context_->check(context_->api().cuEventRecord(copied_, stream), "cuEventRecord");
  copying_ = true;
}

void PinnedStaging::copy_to_host(void* destination, CUdeviceptr source, size_t bytes, CUstream stream) {
  deliver();
  reserve(bytes);
  context_->check(context_->api().cuMemcpyDtoHAsync(host_, source, bytes, stream), "cuMemcpyDtoHAsync");
  context_->check(context_->api().cuEventRecord(copied_, stream), "cuEventRecord");
  copying_ = true;
  destination_ = destination;
  pending_bytes_ = bytes;
}

void PinnedStaging::deliver() {
  if (!destination_) return;
  context_->make_current();
  wait_for_last_copy();
  std::memcpy(destination_, host_, pending_bytes_);
  destination_ = nullptr;
  pending_bytes_ = 0;
}

}  // namespace depthtrack::compute::cuda
