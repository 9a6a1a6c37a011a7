#include "compute/cuda/cuda_nvrtc_api.hpp"

#include <dlfcn.h>

#include <algorithm>
#include <depthtrack/error.hpp>
#include <filesystem>
#include <vector>

namespace depthtrack::compute::cuda {
namespace {

struct Loaded {
  NvrtcApi api;
  std::string failure;  // empty when NVRTC is usable
};

// The sonames of the CUDA releases this code is written for, then the toolkit's own folder for
// machines where the toolkit is installed but not on the loader's path.
std::vector<std::string> candidates() {
  std::vector<std::string> names = {"libnvrtc.so.13", "libnvrtc.so.12", "libnvrtc.so"};
  std::vector<std::string> found;
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator("/usr/local/cuda/lib64", error))
    if (entry.path().filename().string().rfind("libnvrtc.so", 0) == 0) found.push_back(entry.path().string());
  std::sort(found.rbegin(), found.rend());  // newest version first
  names.insert(names.end(), found.begin(), found.end());
  return names;
}

template <class F>
bool resolve(void* library, F& function, const char* name) {
  function = reinterpret_cast<F>(dlsym(library, name));
  return function != nullptr;
}

// Fills api from one library; false (with why) when it cannot be opened or lacks a function.
bool try_library(const std::string& name, NvrtcApi& api, std::string& why) {
  void* library = dlopen(name.c_str(), RTLD_NOW | RTLD_LOCAL);  // never closed, like the driver
  if (!library) {
    const char* error = dlerror();
    why = error ? error : name + " could not be opened";
    return false;
  }
  NvrtcApi candidate;
#define DT_NVRTC_RESOLVE(f)                 \
  if (!resolve(library, candidate.f, #f)) { \
    why = name + " lacks " #f;              \
    return false;                           \
  }
  DT_NVRTC_FUNCTIONS(DT_NVRTC_RESOLVE)
#undef DT_NVRTC_RESOLVE
#define DT_NVRTC_RESOLVE_OPTIONAL(f) resolve(library, candidate.f, #f);
  DT_NVRTC_OPTIONAL_FUNCTIONS(DT_NVRTC_RESOLVE_OPTIONAL)
#undef DT_NVRTC_RESOLVE_OPTIONAL
  if (candidate.nvrtcVersion(&candidate.major, &candidate.minor) != NVRTC_SUCCESS) {
    why = name + ": nvrtcVersion failed";
    return false;
  }
  candidate.library = name;
  api = candidate;
  return true;
}

Loaded load() {
  Loaded out;
  std::string tried, last_error;
  for (const std::string& name : candidates()) {
    if (try_library(name, out.api, last_error)) return out;
    tried += (tried.empty() ? "" : ", ") + name;
  }
  out.failure = "no usable NVRTC library (tried " + tried + "; last error: " + last_error + ")";
  return out;
}

const Loaded& loaded() {
  static const Loaded instance = load();
  return instance;
}

}  // namespace

const NvrtcApi* nvrtc_api() {
  return loaded().failure.empty() ? &loaded().api : nullptr;
}

const std::string& nvrtc_failure() {
  return loaded().failure;
}

const NvrtcApi& require_nvrtc() {
  if (const NvrtcApi* api = nvrtc_api()) return *api;
  throw BackendError("NVRTC is unavailable: " + nvrtc_failure());
}

}  // namespace depthtrack::compute::cuda
