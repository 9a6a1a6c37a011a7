#include "compute/cuda/cuda_memory.hpp"

#include <depthtrack/error.hpp>

namespace depthtrack::compute::cuda {
namespace {

std::string mebibytes(size_t bytes) {
  return std::to_string(bytes / (1024 * 1024)) + " MiB";
}

}  // namespace

CudaMemory::CudaMemory(std::shared_ptr<const Context> context, size_t bytes)
    : context_(std::move(context)), bytes_(bytes) {
  const Context& ctx = *context_;
  ctx.make_current();
  if (bytes == 0)
    throw BackendError("cannot allocate 0 bytes on " + ctx.where() + ": a buffer needs at least one byte");
  size_t free = 0, total = 0;
  ctx.check(ctx.api().cuMemGetInfo(&free, &total), "cuMemGetInfo");
  // Refused up front with both numbers; the driver's own refusal would only say "out of memory".
  if (bytes > free)
    throw BackendError("cannot allocate " + std::to_string(bytes) + " bytes (" + mebibytes(bytes) + ") on " +
                       ctx.where() + ": only " + std::to_string(free) + " bytes (" + mebibytes(free) + ") of " +
                       mebibytes(total) + " are free");
  ctx.check(ctx.api().cuMemAlloc(&pointer_, bytes), "cuMemAlloc");
}

CudaMemory::~CudaMemory() {
  // A destructor cannot throw; a failure here (driver shutting down at exit) leaks nothing that lives on.
  if (context_->try_make_current()) context_->api().cuMemFree(pointer_);
}

const CudaMemory& cuda_memory(const DeviceMemory& memory, const Context& context, const std::string& use) {
  return cuda_memory(memory, context.device(), context.where(), use);
}

const CudaMemory& cuda_memory(const DeviceMemory& memory, CUdevice device, const std::string& where,
                              const std::string& use) {
  const auto* cuda = dynamic_cast<const CudaMemory*>(&memory);
  if (!cuda) throw InputError(use + " on " + where + ": the memory is not CUDA memory");
  // Queues of one device share its primary context, so their memory is interchangeable.
  if (cuda->context().device() != device)
    throw InputError(use + " on " + where + ": the memory belongs to " + cuda->context().where());
  return *cuda;
}

}  // namespace depthtrack::compute::cuda
