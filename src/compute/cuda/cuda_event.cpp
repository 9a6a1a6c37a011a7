#include "compute/cuda/cuda_event.hpp"

#include <depthtrack/error.hpp>

namespace depthtrack::compute::cuda {

CudaEvent::CudaEvent(std::shared_ptr<const Context> context) : context_(std::move(context)) {
  const Context& ctx = *context_;
  ctx.make_current();
  // CU_EVENT_DEFAULT keeps timing on (CU_EVENT_DISABLE_TIMING would make elapsed_ms impossible).
  ctx.check(ctx.api().cuEventCreate(&start_, CU_EVENT_DEFAULT), "cuEventCreate");
  if (const CUresult status = ctx.api().cuEventCreate(&end_, CU_EVENT_DEFAULT); status != CUDA_SUCCESS) {
    ctx.api().cuEventDestroy(start_);
    ctx.check(status, "cuEventCreate");
  }
}

CudaEvent::~CudaEvent() {
  // Destroying an event whose work is still pending is allowed: the driver frees it when done.
  if (!context_->try_make_current()) return;
  context_->api().cuEventDestroy(start_);
  context_->api().cuEventDestroy(end_);
}

void CudaEvent::record_start(CUstream stream) {
  context_->check(context_->api().cuEventRecord(start_, stream), "cuEventRecord");
}

void CudaEvent::record_end(CUstream stream) {
  context_->check(context_->api().cuEventRecord(end_, stream), "cuEventRecord");
}

void CudaEvent::wait() {
  context_->make_current();
  context_->check(context_->api().cuEventSynchronize(end_), "cuEventSynchronize");
}

double CudaEvent::elapsed_ms() {
  wait();
  float milliseconds = 0.0f;
  context_->check(context_->api().cuEventElapsedTime(&milliseconds, start_, end_), "cuEventElapsedTime");
  return static_cast<double>(milliseconds);
}

std::optional<double> CudaEvent::elapsed_since_ms(Event& earlier) {
  auto* first = dynamic_cast<CudaEvent*>(&earlier);
  if (!first || first->context_ != context_) return std::nullopt;
  wait();
  float milliseconds = 0.0f;
  context_->check(context_->api().cuEventElapsedTime(&milliseconds, first->start_, end_), "cuEventElapsedTime");
  return static_cast<double>(milliseconds);
}

}  // namespace depthtrack::compute::cuda
