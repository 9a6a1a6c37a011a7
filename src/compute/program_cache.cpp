#include "compute/program_cache.hpp"

#include <algorithm>

#include "compute/kernel_sources.hpp"
#include "core/stopwatch.hpp"

namespace depthtrack::compute {

std::shared_ptr<Program> ProgramCache::program(const std::string& file, const std::vector<std::string>& definitions) {
  std::lock_guard lock(mutex_);
  auto& slot = programs_[{file, definitions}];
  if (!slot) {
    const Stopwatch build;
    slot = queue_.build(file, kernel_source(file), definitions);  // a failed build leaves the slot empty
    records_.push_back({file, definitions, build.elapsed_ms(), slot->loaded_from_disk()});
  }
  return slot;
}

size_t ProgramCache::builds() const {
  std::lock_guard lock(mutex_);
  return records_.size();
}

size_t ProgramCache::loaded_from_disk() const {
  std::lock_guard lock(mutex_);
  return static_cast<size_t>(
      std::count_if(records_.begin(), records_.end(), [](const BuildRecord& r) { return r.loaded_from_disk; }));
}

std::vector<ProgramCache::BuildRecord> ProgramCache::records() const {
  std::lock_guard lock(mutex_);
  return records_;
}

}  // namespace depthtrack::compute
