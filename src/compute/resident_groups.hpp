#pragma once
// How many groups of a kernel each compute unit should hold at once: a program's DT_RESIDENT_GROUPS, which
// cl/ kernels marked DT_RESIDENCY turn into CUDA's __launch_bounds__ (OpenCL's compilers choose alone).
#include <algorithm>
#include <cstddef>

#include "compute/device_info.hpp"

namespace depthtrack::compute {

// As many groups of group_bytes of work-group memory as a unit holds, but no more than leave 64 registers a
// work-item: NVRTC 13 fits render_weigh and rasterize in 63 without spilling (in 56 they spill) where it
// otherwise takes 70-74, which leaves one or two groups fewer resident than memory allows (NVIDIA's OpenCL
// compiler takes 46-47). 0 where the device does not say what a unit holds (OpenCL): no hint.
inline size_t resident_groups(size_t group_bytes, size_t group_size, const DeviceInfo& device) {
  constexpr size_t kRegisterFloor = 64;
  if (device.local_memory_per_unit == 0 || device.registers_per_unit == 0 || group_size == 0) return 0;
  const size_t by_memory = device.local_memory_per_unit / (group_bytes + device.local_memory_reserved);
  const size_t by_registers = device.registers_per_unit / (group_size * kRegisterFloor);
  return std::max<size_t>(1, std::min(by_memory, by_registers));
}

}  // namespace depthtrack::compute
