#include "compute/cuda/cuda_context.hpp"

#include "compute/cuda/cuda_device_query.hpp"
#include "compute/cuda/cuda_errors.hpp"

namespace depthtrack::compute::cuda {

Context::Context(int ordinal) : api_(require_driver()), info_(query_device(api_, ordinal)) {
  where_ = info_.name + " (" + info_.selector + ")";
  check(api_.cuDeviceGet(&device_, ordinal), "cuDeviceGet");
  compute_capability_ = cuda::compute_capability(api_, device_);
  limits_ = device_limits(api_, device_);
  check(api_.cuDevicePrimaryCtxRetain(&context_, device_), "cuDevicePrimaryCtxRetain");
}

Context::~Context() {
  // Errors are ignored: at process exit the driver may already be shutting down.
  api_.cuDevicePrimaryCtxRelease(device_);
}

void Context::make_current() const {
  check(api_.cuCtxSetCurrent(context_), "cuCtxSetCurrent");
}

void Context::check(CUresult status, const char* call) const {
  cuda::check(status, call, where_);
}

}  // namespace depthtrack::compute::cuda
