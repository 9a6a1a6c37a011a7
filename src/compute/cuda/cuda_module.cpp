#include "compute/cuda/cuda_module.hpp"

#include <cstdint>
#include <depthtrack/error.hpp>

#include "compute/cuda/cuda_errors.hpp"
#include "compute/cuda/cuda_kernel.hpp"

namespace depthtrack::compute::cuda {

Module::Module(std::shared_ptr<const Context> context, const CompiledImage& image, const std::string& program)
    : context_(std::move(context)) {
  const Context& ctx = *context_;
  ctx.make_current();
  // The JIT's log says why PTX was refused (e.g. a PTX version newer than the driver).
  char log[4096] = {};
  CUjit_option options[] = {CU_JIT_ERROR_LOG_BUFFER, CU_JIT_ERROR_LOG_BUFFER_SIZE_BYTES};
  void* values[] = {log, reinterpret_cast<void*>(static_cast<std::uintptr_t>(sizeof log - 1))};
  const CUresult status = ctx.api().cuModuleLoadDataEx(&module_, image.image.c_str(), 2, options, values);
  if (status != CUDA_SUCCESS)
    throw BackendError("cuModuleLoadDataEx failed: " + cuda_error_text(ctx.api(), status) + " loading program '" +
                       program + "' (" + (image.is_cubin ? "cubin for " : "PTX for ") + image.target + ", options " +
                       image.options + ") on " + ctx.where() + (log[0] ? std::string("\nJIT log:\n") + log : ""));
}

Module::~Module() {
  if (context_->try_make_current()) context_->api().cuModuleUnload(module_);
}

CudaProgram::CudaProgram(std::shared_ptr<const Context> context, const std::string& name, const std::string& source,
                         const CompiledImage& image, bool from_disk)
    : module_(std::make_shared<const Module>(std::move(context), image, name)),
      name_(name),
      kernel_names_(kernel_names(source)),
      from_disk_(from_disk) {}

std::unique_ptr<Kernel> CudaProgram::kernel(const std::string& name) {
  const Context& ctx = *module_->context();
  ctx.make_current();
  CUfunction function = nullptr;
  const CUresult status = ctx.api().cuModuleGetFunction(&function, module_->get(), name.c_str());
  if (status == CUDA_ERROR_NOT_FOUND) {
    std::string names;
    for (const std::string& known : kernel_names_) names += (names.empty() ? "" : ", ") + known;
    throw BackendError("program '" + name_ + "' has no kernel '" + name + "' (cuModuleGetFunction: " +
                       cuda_error_text(ctx.api(), status) + "); its kernels: " + (names.empty() ? "none" : names));
  }
  ctx.check(status, "cuModuleGetFunction");
  return std::make_unique<CudaKernel>(module_, function, name);
}

}  // namespace depthtrack::compute::cuda
