#include "compute/cuda/cuda_driver_api.hpp"

#include <dlfcn.h>

#include <cstring>
#include <depthtrack/error.hpp>
#include <utility>

#include "compute/cuda/cuda_errors.hpp"

// The name cuda.h maps a function to, as a string: DT_CUDA_NAME(cuMemAlloc) is "cuMemAlloc_v2".
#define DT_CUDA_NAME2(f) #f
#define DT_CUDA_NAME(f) DT_CUDA_NAME2(f)

namespace depthtrack::compute::cuda {
namespace {

struct Loaded {
  DriverApi api;
  void* library = nullptr;
  std::string failure;  // empty when the driver is usable
};

// Versioned names that a driver older than the headers may lack, with the older name of the
// same signature to use instead (cuEventElapsedTime_v2 came with CUDA 12.8).
const char* older_name(const char* name) {
  if (std::strcmp(name, "cuEventElapsedTime_v2") == 0) return "cuEventElapsedTime";
  return nullptr;
}

template <class F>
bool resolve(void* library, F& function, const char* name) {
  void* symbol = dlsym(library, name);
  if (!symbol && older_name(name)) symbol = dlsym(library, older_name(name));
  function = reinterpret_cast<F>(symbol);
  return symbol != nullptr;
}

Loaded load() {
  Loaded out;
  // Never closed: the driver does not like being unloaded, and objects freed at exit still call it.
  void* library = dlopen("libcuda.so.1", RTLD_NOW | RTLD_LOCAL);
  if (!library) {
    const char* why = dlerror();
    const std::string detail = why ? why : "";
    out.failure = detail.find("No such file") != std::string::npos || detail.empty()
                      ? "libcuda.so.1 not found (no NVIDIA driver)"
                      : "libcuda.so.1 could not be loaded: " + detail;
    return out;
  }
  out.library = library;
  std::string missing;
#define DT_CUDA_RESOLVE(f)                           \
  if (!resolve(library, out.api.f, DT_CUDA_NAME(f))) \
    missing += std::string(missing.empty() ? "" : ", ") + DT_CUDA_NAME(f);
  DT_CUDA_DRIVER_FUNCTIONS(DT_CUDA_RESOLVE)
#undef DT_CUDA_RESOLVE
  if (!missing.empty()) {
    out.failure = "libcuda.so.1 lacks " + missing + " (the NVIDIA driver is too old for this build)";
    return out;
  }
#define DT_CUDA_RESOLVE_OPTIONAL(f) resolve(library, out.api.f, DT_CUDA_NAME(f));
  DT_CUDA_DRIVER_OPTIONAL_FUNCTIONS(DT_CUDA_RESOLVE_OPTIONAL)
#undef DT_CUDA_RESOLVE_OPTIONAL
  // cuInit fails without a usable GPU (CUDA_ERROR_NO_DEVICE) or with a broken driver install.
  if (const CUresult status = out.api.cuInit(0); status != CUDA_SUCCESS)
    out.failure = "cuInit failed: " + cuda_error_text(out.api, status);
  return out;
}

const Loaded& loaded() {
  static const Loaded instance = load();  // C++ guarantees one thread-safe initialization
  return instance;
}

}  // namespace

const DriverApi* driver_api() {
  return loaded().failure.empty() ? &loaded().api : nullptr;
}

const std::string& driver_failure() {
  return loaded().failure;
}

void* driver_symbol(const char* name) {
  return loaded().library && loaded().failure.empty() ? dlsym(loaded().library, name) : nullptr;
}

const DriverApi& require_driver() {
  if (const DriverApi* api = driver_api()) return *api;
  throw BackendError("CUDA is unavailable: " + driver_failure());
}

}  // namespace depthtrack::compute::cuda
