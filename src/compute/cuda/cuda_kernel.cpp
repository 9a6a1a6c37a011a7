#include "compute/cuda/cuda_kernel.hpp"

#include <algorithm>
#include <cstddef>
#include <depthtrack/error.hpp>

#include "compute/cuda/cuda_memory.hpp"

namespace depthtrack::compute::cuda {
namespace {

// The parameter sizes the compiled kernel declares, or nullopt when the driver cannot tell.
std::optional<std::vector<size_t>> query_parameter_sizes(const DriverApi& api, CUfunction function) {
  if (!api.cuFuncGetParamInfo) return std::nullopt;
  std::vector<size_t> sizes;
  // The driver answers CUDA_ERROR_INVALID_VALUE past the last parameter.
  for (size_t index = 0;; ++index) {
    size_t offset = 0, size = 0;
    if (api.cuFuncGetParamInfo(function, index, &offset, &size) != CUDA_SUCCESS) break;
    sizes.push_back(size);
  }
  return sizes;
}

}  // namespace

CudaKernel::CudaKernel(std::shared_ptr<const Module> module, CUfunction function, std::string name)
    : module_(std::move(module)), function_(function), name_(std::move(name)) {
  const Context& ctx = context();
  int threads = 0;
  ctx.check(ctx.api().cuFuncGetAttribute(&threads, CU_FUNC_ATTRIBUTE_MAX_THREADS_PER_BLOCK, function_),
            "cuFuncGetAttribute");
  max_threads_ = static_cast<size_t>(threads);
  parameter_sizes_ = query_parameter_sizes(ctx.api(), function_);
}

// A frame sets a few hundred arguments: the texts are made only for an error, and an argument's bytes
// reuse its storage.
std::string CudaKernel::describe_arg(unsigned index) const {
  return "argument " + std::to_string(index) + " of kernel '" + name_ + "'";
}

void CudaKernel::set_arg(unsigned index, const DeviceMemory& memory) {
  const auto* cuda = dynamic_cast<const CudaMemory*>(&memory);
  if (!cuda || cuda->context().device() != context().device())
    cuda = &cuda_memory(memory, context(), describe_arg(index));  // throws, naming what is wrong
  const CUdeviceptr pointer = cuda->pointer();
  set_arg_bytes(index, &pointer, sizeof pointer);
}

void CudaKernel::set_arg_bytes(unsigned index, const void* value, size_t size) {
  if (!value || size == 0) throw InputError(describe_arg(index) + ": no value given");
  if (parameter_sizes_) {
    if (index >= parameter_sizes_->size())
      throw InputError(describe_arg(index) + ": the kernel takes " + std::to_string(parameter_sizes_->size()) +
                       " arguments");
    if (size != (*parameter_sizes_)[index])
      throw InputError(describe_arg(index) + " is " + std::to_string(size) + " bytes; the kernel declares " +
                       std::to_string((*parameter_sizes_)[index]));
  }
  if (arguments_.size() <= index) arguments_.resize(index + 1);
  const auto* bytes = static_cast<const unsigned char*>(value);
  if (arguments_[index])
    arguments_[index]->assign(bytes, bytes + size);
  else
    arguments_[index].emplace(bytes, bytes + size);
}

LaunchLimits CudaKernel::limits() const {
  LaunchLimits limits = context().limits();
  limits.max_threads = std::min(limits.max_threads, max_threads_);
  return limits;
}

std::vector<void*> CudaKernel::argument_pointers() {
  const size_t count = parameter_sizes_ ? parameter_sizes_->size() : arguments_.size();
  std::vector<void*> pointers;
  for (size_t index = 0; index < count; ++index) {
    if (index >= arguments_.size() || !arguments_[index])
      throw InputError("launch of kernel '" + name_ + "': argument " + std::to_string(index) + " of " +
                       std::to_string(count) + " was never set");
    pointers.push_back(arguments_[index]->data());
  }
  return pointers;
}

void CudaKernel::copy_arguments(std::vector<unsigned char>& bytes, std::vector<size_t>& offsets) const {
  constexpr size_t kAlign = alignof(std::max_align_t);
  const size_t count = parameter_sizes_ ? parameter_sizes_->size() : arguments_.size();
  for (size_t index = 0; index < count; ++index) {
    if (index >= arguments_.size() || !arguments_[index])
      throw InputError("launch of kernel '" + name_ + "': argument " + std::to_string(index) + " of " +
                       std::to_string(count) + " was never set");
    const std::vector<unsigned char>& value = *arguments_[index];
    const size_t offset = (bytes.size() + kAlign - 1) / kAlign * kAlign;
    bytes.resize(offset + value.size());
    std::copy(value.begin(), value.end(), bytes.begin() + static_cast<std::ptrdiff_t>(offset));
    offsets.push_back(offset);
  }
}

}  // namespace depthtrack::compute::cuda
