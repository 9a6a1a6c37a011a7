#include "interop/cuda/exportable_memory.hpp"

#include <depthtrack/error.hpp>

#include "compute/cuda/cuda_driver_api.hpp"

namespace depthtrack::interop {

namespace {
// The CUDA ordinal of the device with this UUID, or -1.
int ordinal_of(const compute::cuda::DriverApi& api, const std::array<unsigned char, 16>& uuid) {
  int count = 0;
  if (api.cuDeviceGetCount(&count) != CUDA_SUCCESS || !api.cuDeviceGetUuid) return -1;
  for (int i = 0; i < count; ++i) {
    CUdevice device = 0;
    CUuuid id{};
    if (api.cuDeviceGet(&device, i) != CUDA_SUCCESS || api.cuDeviceGetUuid(&id, device) != CUDA_SUCCESS) continue;
    bool same = true;
    for (size_t k = 0; k < 16; ++k) same = same && static_cast<unsigned char>(id.bytes[k]) == uuid[k];
    if (same) return i;
  }
  return -1;
}

CUmemAllocationProp exportable_on(CUdevice device) {
  CUmemAllocationProp prop{};
  prop.type = CU_MEM_ALLOCATION_TYPE_PINNED;
  prop.location.type = CU_MEM_LOCATION_TYPE_DEVICE;
  prop.location.id = device;
  prop.requestedHandleTypes = CU_MEM_HANDLE_TYPE_POSIX_FILE_DESCRIPTOR;
  return prop;
}
}  // namespace

std::unique_ptr<ExportableMemory> ExportableMemory::make(const std::optional<std::array<unsigned char, 16>>& uuid,
                                                         size_t bytes, std::string& why_not) {
  const compute::cuda::DriverApi* api = compute::cuda::driver_api();
  if (!api) {
    why_not = "no CUDA driver to allocate exportable memory (" + compute::cuda::driver_failure() + ")";
    return nullptr;
  }
  if (!api->cuMemCreate || !api->cuMemExportToShareableHandle || !api->cuMemGetAllocationGranularity ||
      !api->cuMemRelease) {
    why_not = "the CUDA driver lacks virtual memory management";
    return nullptr;
  }
  const int ordinal = uuid ? ordinal_of(*api, *uuid) : -1;
  if (ordinal < 0) {
    why_not = "no CUDA device with the compute device's UUID";
    return nullptr;
  }
  auto context = std::make_shared<const compute::cuda::Context>(ordinal);
  context->make_current();
  const CUmemAllocationProp prop = exportable_on(context->device());
  size_t granularity = 0;
  context->check(api->cuMemGetAllocationGranularity(&granularity, &prop, CU_MEM_ALLOC_GRANULARITY_MINIMUM),
                 "cuMemGetAllocationGranularity");
  const size_t rounded = (bytes + granularity - 1) / granularity * granularity;
  CUmemGenericAllocationHandle handle = 0;
  context->check(api->cuMemCreate(&handle, rounded, &prop, 0), "cuMemCreate (exportable atlas memory)");
  return std::unique_ptr<ExportableMemory>(new ExportableMemory(std::move(context), handle, rounded));
}

ExportableMemory::ExportableMemory(std::shared_ptr<const compute::cuda::Context> context,
                                   CUmemGenericAllocationHandle handle, size_t bytes)
    : context_(std::move(context)), handle_(handle), bytes_(bytes) {}

ExportableMemory::~ExportableMemory() {
  // Importers hold their own references: the memory lives until the last of them lets go.
  if (context_->try_make_current()) context_->api().cuMemRelease(handle_);
}

int ExportableMemory::export_fd() const {
  int fd = -1;
  context_->make_current();
  context_->check(
      context_->api().cuMemExportToShareableHandle(&fd, handle_, CU_MEM_HANDLE_TYPE_POSIX_FILE_DESCRIPTOR, 0),
      "cuMemExportToShareableHandle");
  return fd;
}

}  // namespace depthtrack::interop
