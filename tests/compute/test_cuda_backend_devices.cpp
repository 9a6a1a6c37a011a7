// The CUDA backend's device list: empty with a reason where there is no NVIDIA driver (CI), the
// machine's GPUs where there is one. The test decides which to expect on its own (libcuda.so.1
// loads, /dev/nvidiactl exists and CUDA_VISIBLE_DEVICES does not hide every GPU), so a GPU machine
// whose backend lists nothing fails.
#include <catch2/catch.hpp>
#include <depthtrack/error.hpp>
#include <iostream>

#if defined(DEPTHTRACK_WITH_CUDA)
#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>

#include "compute/cuda/cuda_backend.hpp"

using namespace depthtrack;

namespace {
bool nvidia_gpu_expected() {
  const char* visible = std::getenv("CUDA_VISIBLE_DEVICES");
  if (visible && (std::string(visible).empty() || std::string(visible) == "-1")) return false;  // hidden on purpose
  // Left open, as the backend leaves it: the driver does not like being unloaded.
  const bool loads = dlopen("libcuda.so.1", RTLD_LAZY | RTLD_LOCAL) != nullptr;
  return loads && std::filesystem::exists("/dev/nvidiactl");
}

std::string open_error(unsigned ordinal) {
  try {
    compute::cuda::open(ordinal);
  } catch (const BackendError& e) {
    return e.what();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}
}  // namespace

TEST_CASE("CUDA devices: none and a reason without a driver, the GPUs with one", "[cuda]") {
  const auto devices = compute::cuda::devices();
  if (!nvidia_gpu_expected()) {
    CHECK(devices.empty());
    const std::string reason = compute::cuda::unavailable_reason();
    CHECK_FALSE(reason.empty());
    const std::string error = open_error(0);
    CHECK(error.find(reason) != std::string::npos);
    return;
  }
  INFO("unavailable_reason: " << compute::cuda::unavailable_reason());
  REQUIRE_FALSE(devices.empty());
  CHECK(devices[0].selector == "cuda:0");
  for (const auto& device : devices) {
    CHECK_FALSE(device.name.empty());
    CHECK(device.backend == "cuda");
    CHECK(device.is_gpu);
    CHECK(device.global_memory > 0);
    CHECK(device.max_work_group_size >= 32);
    CHECK(device.compute_units > 0);
    CHECK(device.version.rfind("CUDA ", 0) == 0);
    CHECK(device.version.find("(sm_") != std::string::npos);
  }
  // One past the last device is the caller's mistake, and says which devices exist.
  const std::string error = open_error(static_cast<unsigned>(devices.size()));
  CHECK(error.find("cuda:0") != std::string::npos);
}

#else

TEST_CASE("CUDA backend tests need the backend", "[cuda]") {
  std::cout << "SKIPPED: the CUDA backend is not built into this test suite (DEPTHTRACK_WITH_CUDA is not defined "
               "for it)\n";
}

#endif
