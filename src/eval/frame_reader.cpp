#include "eval/frame_reader.hpp"

#include <depthtrack/error.hpp>
#include <string>

namespace depthtrack {

FrameReader::FrameReader(const Sequence& sequence, size_t ahead)
    : sequence_(sequence), ahead_(ahead == 0 ? 1 : ahead), thread_([this] { read_all(); }) {}

FrameReader::~FrameReader() {
  {
    const std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  changed_.notify_all();
  thread_.join();
}

void FrameReader::read_all() {
  for (size_t i = 0; i < sequence_.frames.size(); ++i) {
    Slot slot;
    try {
      slot.depth = sequence_.load_depth(i);
    } catch (const InputError& e) {
      slot.error = std::make_exception_ptr(InputError("frame " + sequence_.frames[i].name + ": " + e.what()));
    } catch (...) {
      slot.error = std::current_exception();
    }
    const bool failed = slot.error != nullptr;
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [this] { return stopping_ || ready_.size() < ahead_; });
    if (stopping_) return;
    ready_.push_back(std::move(slot));
    lock.unlock();
    changed_.notify_all();
    if (failed) return;  // the tracker stops at the failed frame; reading on would be wasted work
  }
}

DepthImage FrameReader::next() {
  if (delivered_ >= sequence_.frames.size())
    throw InputError("FrameReader::next: all " + std::to_string(sequence_.frames.size()) + " frames were already read");
  if (failed_) throw InputError("FrameReader::next: reading stopped at the frame that failed to load");
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [this] { return !ready_.empty(); });
  Slot slot = std::move(ready_.front());
  ready_.pop_front();
  lock.unlock();
  changed_.notify_all();
  ++delivered_;
  failed_ = slot.error != nullptr;
  if (failed_) std::rethrow_exception(slot.error);
  return std::move(slot.depth);
}

}  // namespace depthtrack
