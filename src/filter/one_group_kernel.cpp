#include "filter/one_group_kernel.hpp"

#include <algorithm>
#include <depthtrack/error.hpp>

namespace depthtrack {

size_t one_group_size(size_t particles, const compute::DeviceInfo& device) {
  if (particles < kWideGroupParticles) return kNarrowGroup;
  const size_t limit =
      device.max_work_group_size > 0 ? std::min(device.max_work_group_size, kWidestGroup) : kWidestGroup;
  size_t group = kNarrowGroup;
  while (group * 2 <= limit) group *= 2;
  return group;
}

OneGroupKernel build_one_group_kernel(compute::ProgramCache& programs, const std::string& file, const std::string& name,
                                      const std::vector<std::string>& definitions, size_t group) {
  for (;;) {
    std::vector<std::string> all = {"DT_GROUP_SIZE=" + std::to_string(group)};
    all.insert(all.end(), definitions.begin(), definitions.end());
    OneGroupKernel built;
    built.program = programs.program(file, all);
    built.kernel = built.program->kernel(name);
    built.group = group;
    const size_t limit = built.kernel->max_group_size();
    if (limit == 0 || limit >= group) return built;
    if (group == 1)
      throw BackendError("kernel '" + name + "' of " + file + " fits no work-group on this device (limit " +
                         std::to_string(limit) + ")");
    group /= 2;  // a power of two, as the kernels' group sums need
  }
}

}  // namespace depthtrack
