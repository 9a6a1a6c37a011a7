#include "compute/cuda/cuda_device_query.hpp"

#include "compute/cuda/cuda_errors.hpp"

namespace depthtrack::compute::cuda {

std::string format_cuda_version(int version) {
  return std::to_string(version / 1000) + "." + std::to_string(version % 1000 / 10);
}

int device_attribute(const DriverApi& api, CUdevice device, CUdevice_attribute attribute) {
  int value = 0;
  check(api.cuDeviceGetAttribute(&value, attribute, device), "cuDeviceGetAttribute", "");
  return value;
}

namespace {
// An attribute that older drivers may not know: 0 where the driver refuses it.
size_t optional_attribute(const DriverApi& api, CUdevice device, CUdevice_attribute attribute) {
  int value = 0;
  return api.cuDeviceGetAttribute(&value, attribute, device) == CUDA_SUCCESS && value > 0 ? static_cast<size_t>(value)
                                                                                          : 0;
}
}  // namespace

int compute_capability(const DriverApi& api, CUdevice device) {
  return device_attribute(api, device, CU_DEVICE_ATTRIBUTE_COMPUTE_CAPABILITY_MAJOR) * 10 +
         device_attribute(api, device, CU_DEVICE_ATTRIBUTE_COMPUTE_CAPABILITY_MINOR);
}

DeviceInfo query_device(const DriverApi& api, int ordinal) {
  CUdevice device = 0;
  const std::string selector = "cuda:" + std::to_string(ordinal);
  check(api.cuDeviceGet(&device, ordinal), "cuDeviceGet", selector);
  char name[256] = {};
  check(api.cuDeviceGetName(name, static_cast<int>(sizeof name - 1), device), "cuDeviceGetName", selector);
  int driver = 0;
  check(api.cuDriverGetVersion(&driver), "cuDriverGetVersion", selector);
  size_t total = 0;
  check(api.cuDeviceTotalMem(&total, device), "cuDeviceTotalMem", selector);

  DeviceInfo info;
  info.backend = "cuda";
  info.selector = selector;
  info.platform = "NVIDIA CUDA";
  info.vendor = "NVIDIA";
  info.name = name;
  info.driver = format_cuda_version(driver);
  info.version = "CUDA " + info.driver + " (sm_" + std::to_string(compute_capability(api, device)) + ")";
  info.is_gpu = true;
  info.global_memory = total;
  info.max_allocation = total;  // CUDA has no per-allocation limit below the memory itself
  info.local_memory =
      static_cast<size_t>(device_attribute(api, device, CU_DEVICE_ATTRIBUTE_MAX_SHARED_MEMORY_PER_BLOCK));
  info.local_memory_per_unit =
      optional_attribute(api, device, CU_DEVICE_ATTRIBUTE_MAX_SHARED_MEMORY_PER_MULTIPROCESSOR);
  info.local_memory_reserved = optional_attribute(api, device, CU_DEVICE_ATTRIBUTE_RESERVED_SHARED_MEMORY_PER_BLOCK);
  info.registers_per_unit = optional_attribute(api, device, CU_DEVICE_ATTRIBUTE_MAX_REGISTERS_PER_MULTIPROCESSOR);
  info.max_work_group_size =
      static_cast<size_t>(device_attribute(api, device, CU_DEVICE_ATTRIBUTE_MAX_THREADS_PER_BLOCK));
  info.compute_units = device_attribute(api, device, CU_DEVICE_ATTRIBUTE_MULTIPROCESSOR_COUNT);
  info.gl_sharing = true;       // CUDA-GL interop (cuGraphicsGLRegisterImage) is part of every Linux driver
  info.external_memory = true;  // cuImportExternalMemory (opaque fd)
  info.fp64 = true;
  info.int64_atomics = true;      // atomicMin on unsigned long long: sm_35 on, below what NVRTC targets
  info.subgroups = true;          // warps
  info.replayed_launches = true;  // the queue's batches become graphs (cuda_launch_graph.hpp)
  CUuuid uuid{};
  if (api.cuDeviceGetUuid && api.cuDeviceGetUuid(&uuid, device) == CUDA_SUCCESS) {
    info.uuid.emplace();
    for (size_t i = 0; i < 16; ++i) (*info.uuid)[i] = static_cast<unsigned char>(uuid.bytes[i]);
  }
  return info;
}

LaunchLimits device_limits(const DriverApi& api, CUdevice device) {
  LaunchLimits limits;
  limits.max_threads = static_cast<size_t>(device_attribute(api, device, CU_DEVICE_ATTRIBUTE_MAX_THREADS_PER_BLOCK));
  const CUdevice_attribute block[3] = {CU_DEVICE_ATTRIBUTE_MAX_BLOCK_DIM_X, CU_DEVICE_ATTRIBUTE_MAX_BLOCK_DIM_Y,
                                       CU_DEVICE_ATTRIBUTE_MAX_BLOCK_DIM_Z};
  const CUdevice_attribute grid[3] = {CU_DEVICE_ATTRIBUTE_MAX_GRID_DIM_X, CU_DEVICE_ATTRIBUTE_MAX_GRID_DIM_Y,
                                      CU_DEVICE_ATTRIBUTE_MAX_GRID_DIM_Z};
  for (int d = 0; d < 3; ++d) {
    limits.max_block[d] = static_cast<size_t>(device_attribute(api, device, block[d]));
    limits.max_grid[d] = static_cast<size_t>(device_attribute(api, device, grid[d]));
  }
  return limits;
}

}  // namespace depthtrack::compute::cuda
