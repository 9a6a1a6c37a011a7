#pragma once
// What a compute device is, as `depthtrack info` and benchmark rows report it.
#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace depthtrack::compute {

struct DeviceInfo {
  std::string backend;   // "opencl" or "cuda"
  std::string selector;  // the string that selects exactly this device, e.g. "opencl:0.1", "cuda:0"
  std::string platform;  // e.g. "Portable Computing Language", "NVIDIA CUDA"
  std::string vendor;
  std::string name;     // e.g. "NVIDIA H100 80GB HBM3"
  std::string driver;   // driver version
  std::string version;  // API version the device offers, e.g. "OpenCL 3.0 CUDA", "CUDA 13.0 (sm_90)"
  bool is_gpu = false;
  size_t global_memory = 0;   // bytes
  size_t max_allocation = 0;  // bytes in one buffer
  size_t local_memory = 0;    // bytes per work-group
  // What one compute unit holds for all the groups resident on it at once, where the API says (CUDA: a
  // multiprocessor's shared memory and registers; each group takes its own shared memory plus
  // local_memory_reserved). 0 where it does not (OpenCL).
  size_t local_memory_per_unit = 0;
  size_t local_memory_reserved = 0;
  size_t registers_per_unit = 0;
  size_t max_work_group_size = 0;
  int compute_units = 0;
  // Extensions that matter to depthtrack.
  bool gl_sharing = false;       // cl_khr_gl_sharing / CUDA-GL interop
  bool external_memory = false;  // cl_khr_external_memory(_opaque_fd) / CUDA external memory
  bool fp64 = false;
  bool subgroups = false;      // cl_khr_subgroups or warps
  bool int64_atomics = false;  // 64-bit atomic min: cl_khr_int64_extended_atomics / CUDA
  // The queue replays a batch of launches as one unit (Queue::begin_batch: CUDA graphs), so a launch
  // costs the host little and many short launches beat one group's long loop (the fit's layout).
  bool replayed_launches = false;
  std::vector<std::string> extensions;  // the full list, where the API has one
  // The GPU's UUID (cuDeviceGetUuid, cl_khr_device_uuid), to find the EGL device on the same GPU.
  std::optional<std::array<unsigned char, 16>> uuid;
};

}  // namespace depthtrack::compute
