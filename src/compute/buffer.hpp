#pragma once
// Typed device buffer: RAII over DeviceMemory, element counts instead of bytes, checked ranges.
#include <depthtrack/error.hpp>
#include <span>
#include <string>
#include <vector>

#include "compute/queue.hpp"

namespace depthtrack::compute {

template <class T>
class HostOverwrite;

template <class T>
class Buffer {
  static_assert(std::is_trivially_copyable_v<T>, "device buffers hold plain data");

 public:
  Buffer() = default;
  Buffer(Queue& queue, size_t count) : queue_(&queue), count_(count), memory_(queue.allocate(count * sizeof(T))) {}

  size_t size() const { return count_; }
  DeviceMemory& memory() { return *memory_; }
  const DeviceMemory& memory() const { return *memory_; }

  // Writes data into elements [offset, offset + data.size()).
  void upload(std::span<const T> data, size_t offset = 0) {
    check_range("upload", offset, data.size());
    queue_->write(*memory_, offset * sizeof(T), data.data(), data.size_bytes());
  }
  // upload() without waiting for the copy (Queue::write_enqueued): data may change once it returns.
  void upload_enqueued(std::span<const T> data, size_t offset = 0) {
    check_range("upload", offset, data.size());
    queue_->write_enqueued(*memory_, offset * sizeof(T), data.data(), data.size_bytes());
  }
  // Reads elements [offset, offset + out.size()) into out.
  void download(std::span<T> out, size_t offset = 0) const {
    check_range("download", offset, out.size());
    queue_->read(*memory_, offset * sizeof(T), out.data(), out.size_bytes());
  }
  // download() without waiting (Queue::read_enqueued): `out` holds the elements after the queue's
  // wait_enqueued_reads(), and must stay valid until then.
  void download_enqueued(std::span<T> out, size_t offset = 0) const {
    check_range("download", offset, out.size());
    queue_->read_enqueued(*memory_, offset * sizeof(T), out.data(), out.size_bytes());
  }
  // Maps elements [offset, offset + count) for the host to overwrite.
  HostOverwrite<T> overwrite(size_t offset, size_t count) {
    check_range("map", offset, count);
    return HostOverwrite<T>(*queue_, *memory_, offset, count);
  }
  std::vector<T> download() const {
    std::vector<T> out(count_);
    download(std::span<T>(out));
    return out;
  }

 private:
  void check_range(const char* what, size_t offset, size_t count) const {
    if (!memory_) throw InputError(std::string("buffer ") + what + ": the buffer was never allocated");
    if (offset > count_ || count > count_ - offset)
      throw InputError(std::string("buffer ") + what + " of elements [" + std::to_string(offset) + ", " +
                       std::to_string(offset + count) + ") is outside a buffer of " + std::to_string(count_) +
                       " elements");
  }

  Queue* queue_ = nullptr;
  size_t count_ = 0;
  std::unique_ptr<DeviceMemory> memory_;
};

// Host access for overwriting elements [offset, offset + count) of a buffer (Queue::map_for_overwrite):
// write through data(), then publish(). Unpublished (an exception on the way), it is unmapped anyway.
template <class T>
class HostOverwrite {
 public:
  HostOverwrite(Queue& queue, DeviceMemory& memory, size_t offset, size_t count)
      : queue_(queue), memory_(memory), data_(static_cast<T*>(queue.map_for_overwrite(memory, offset * sizeof(T),
                                                                                       count * sizeof(T))),
                                              count) {}
  ~HostOverwrite() {
    if (!published_) try {
        queue_.unmap(memory_, data_.data());
      } catch (...) {  // already failing; the first error is the one to report
      }
  }
  HostOverwrite(const HostOverwrite&) = delete;
  HostOverwrite& operator=(const HostOverwrite&) = delete;

  std::span<T> data() { return data_; }
  void publish() {
    published_ = true;
    queue_.unmap(memory_, data_.data());
  }

 private:
  Queue& queue_;
  DeviceMemory& memory_;
  std::span<T> data_;
  bool published_ = false;
};

// A buffer as kernel argument `index`: for the refinement's launch, until it uses Queue::launch(k, range, args...).
template <class T>
void set_arg(Kernel& kernel, unsigned index, const Buffer<T>& buffer) {
  kernel.set_arg(index, buffer.memory());
}

}  // namespace depthtrack::compute
