#pragma once
// Kernels that run in one work-group over every particle (summarize.cl, resample.cl's prefix_sum):
// they add in a fixed order, as the reference does, so they are not spread over groups. Their group
// is kNarrowGroup work-items for small clouds and as wide as the kernel may be on its device (up to
// kWidestGroup) from kWideGroupParticles particles on: at a million particles 128 work-items left one
// multiprocessor waiting on memory for most of the frame (H200: docs/design-notes.md).
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "compute/device_info.hpp"
#include "compute/program_cache.hpp"

namespace depthtrack {

constexpr size_t kNarrowGroup = 128;
constexpr size_t kWidestGroup = 1024;
constexpr size_t kWideGroupParticles = 16384;

// The group to ask for: kNarrowGroup below kWideGroupParticles, else the largest power of two within
// the device's max_work_group_size and kWidestGroup (never below kNarrowGroup).
size_t one_group_size(size_t particles, const compute::DeviceInfo& device);

struct OneGroupKernel {
  std::shared_ptr<compute::Program> program;
  std::unique_ptr<compute::Kernel> kernel;
  size_t group = 0;  // its DT_GROUP_SIZE, and the work-items to launch it with
};

// cl/<file>'s kernel `name` built with DT_GROUP_SIZE = group (plus definitions), halved and built again
// while the kernel's own limit (its registers, Kernel::max_group_size) is below it; an error if even
// one work-item does not fit.
OneGroupKernel build_one_group_kernel(compute::ProgramCache& programs, const std::string& file, const std::string& name,
                                      const std::vector<std::string>& definitions, size_t group);

}  // namespace depthtrack
