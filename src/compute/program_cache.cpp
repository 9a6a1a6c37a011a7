#include "compute/program_cache.hpp"

#include "compute/kernel_sources.hpp"

namespace depthtrack::compute {

std::shared_ptr<Program> ProgramCache::program(const std::string& file, const std::vector<std::string>& definitions) {
  std::lock_guard lock(mutex_);
  auto& slot = programs_[{file, definitions}];
  if (!slot) {
    slot = queue_.build(file, kernel_source(file), definitions);  // a failed build leaves the slot empty
    ++builds_;
  }
  return slot;
}

size_t ProgramCache::builds() const {
  std::lock_guard lock(mutex_);
  return builds_;
}

}  // namespace depthtrack::compute
