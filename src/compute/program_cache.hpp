#pragma once
// Programs built once per device: every tracker on one queue asks the cache for the cl/ file and
// definitions it needs, and the first ask compiles it. Kernels are made per user from the shared
// program (each kernel object keeps its own arguments), so sharing a program shares no state.
#include <cstddef>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "compute/queue.hpp"

namespace depthtrack::compute {

class ProgramCache {
 public:
  // One program made by this cache: how long the build (or the load of its binary) took.
  struct BuildRecord {
    std::string file;
    std::vector<std::string> definitions;
    double ms = 0;
    bool loaded_from_disk = false;
  };

  explicit ProgramCache(Queue& queue) : queue_(queue) {}
  ProgramCache(const ProgramCache&) = delete;
  ProgramCache& operator=(const ProgramCache&) = delete;

  // cl/<file> (compute::kernel_source) built with these definitions, compiled on the first call only.
  std::shared_ptr<Program> program(const std::string& file, const std::vector<std::string>& definitions);
  // How many programs this cache has compiled (not how many were asked for).
  size_t builds() const;
  // How many of those came from the on-disk binary cache instead of a compile.
  size_t loaded_from_disk() const;
  // Every program made, in order (the start-up benchmark's breakdown).
  std::vector<BuildRecord> records() const;
  Queue& queue() const { return queue_; }

 private:
  Queue& queue_;
  mutable std::mutex mutex_;
  std::map<std::pair<std::string, std::vector<std::string>>, std::shared_ptr<Program>> programs_;
  std::vector<BuildRecord> records_;
};

// One open device: its queue and the programs built on it, shared by every filter on it. The cache
// is declared after the queue, so the programs go before the queue that built them.
struct DeviceContext {
  // `against`: what the queue's context was created against and must outlive (the GL context of a
  // cl_khr_gl_sharing context; the compute layer keeps it without knowing what it is), else null.
  explicit DeviceContext(std::unique_ptr<Queue> opened, std::shared_ptr<const void> against = nullptr)
      : made_against(std::move(against)), queue(std::move(opened)), programs(*queue) {}
  // A queue of a filter's own on this device (Queue::another_queue), or nullptr where the backend has one
  // queue only. The programs built here run on it.
  std::unique_ptr<Queue> make_queue() const { return queue->another_queue(); }
  std::shared_ptr<const void> made_against;  // first, so it goes after the queue and its programs
  std::unique_ptr<Queue> queue;
  ProgramCache programs;
};

}  // namespace depthtrack::compute
