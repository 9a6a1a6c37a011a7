#pragma once
// The compute layer's backend boundary: a device with one in-order queue, untyped device memory,
// programs built from source, kernels launched over an nd-range, and events with device timings.
// OpenCL and CUDA implement it (src/compute/opencl, src/compute/cuda); the filter knows only this.
// Every failure throws depthtrack::BackendError naming the API call and the symbolic error
// (CL_OUT_OF_RESOURCES, CUDA_ERROR_OUT_OF_MEMORY), or InputError for a caller's mistake.
#include <concepts>
#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "compute/device_info.hpp"
#include "compute/native_handles.hpp"

namespace depthtrack::compute {

// A device allocation; freed when destroyed.
class DeviceMemory {
 public:
  virtual ~DeviceMemory() = default;
  virtual size_t bytes() const = 0;
};

// A completed or pending piece of device work.
class Event {
 public:
  virtual ~Event() = default;
  virtual void wait() = 0;
  // Device time from start to end of the work, milliseconds (waits for it first).
  virtual double elapsed_ms() = 0;
  // Device time from the start of `earlier` (enqueued before this one on the same queue) to the end of
  // this one, milliseconds: a run of launches with the gaps between them, which adding their
  // elapsed_ms() leaves out. Empty where the backend has no clock common to both (waits for this one).
  virtual std::optional<double> elapsed_since_ms(Event& earlier) {
    (void)earlier;
    return std::nullopt;
  }
};
using EventPtr = std::shared_ptr<Event>;

class Kernel {
 public:
  virtual ~Kernel() = default;
  virtual const std::string& name() const = 0;
  virtual void set_arg(unsigned index, const DeviceMemory& memory) = 0;
  virtual void set_arg_bytes(unsigned index, const void* value, size_t size) = 0;
  // A plain value argument (int, float, unsigned, a struct of them).
  template <class T>
  requires std::is_trivially_copyable_v<T> &&
      (!std::is_base_of_v<DeviceMemory, T>)void set_arg(unsigned index, const T& value) {
    set_arg_bytes(index, &value, sizeof(T));
  }
};

class Program {
 public:
  virtual ~Program() = default;
  // Throws BackendError listing the kernel names if name is not in the program.
  virtual std::unique_ptr<Kernel> kernel(const std::string& name) = 0;
  // True when it came from the on-disk binary cache (compute/program_binary_cache.hpp), not a compile.
  virtual bool loaded_from_disk() const { return false; }
};

// What a launch's arguments may be: device memory, something that holds it (a Buffer<T>: memory()),
// or a trivially copyable value whose size the kernel's parameter has (the backends check it: a
// host size_t for a uint parameter is an error at the launch). bool has no agreed size on devices.
template <class T>
concept HoldsDeviceMemory = requires(const T& t) {
  { t.memory() } -> std::convertible_to<const DeviceMemory&>;
};
template <class T>
concept KernelValue =
    std::is_trivially_copyable_v<T> && !std::is_base_of_v<DeviceMemory, T> && !std::is_same_v<T, bool>;

inline void set_launch_arg(Kernel& kernel, unsigned index, const DeviceMemory& memory) {
  kernel.set_arg(index, memory);
}
template <HoldsDeviceMemory T>
void set_launch_arg(Kernel& kernel, unsigned index, const T& holder) {
  kernel.set_arg(index, holder.memory());
}
template <KernelValue T>
void set_launch_arg(Kernel& kernel, unsigned index, const T& value) {
  kernel.set_arg_bytes(index, &value, sizeof(T));
}
// Sets args as the kernel's arguments 0, 1, ... in order (what launch(kernel, range, args...) does
// first), for launches of the same arguments that follow.
template <class... Args>
void set_launch_args(Kernel& kernel, const Args&... args) {
  unsigned index = 0;
  (set_launch_arg(kernel, index++, args), ...);
}

// OpenCL's nd-range: global work-items per dimension, divisible by the work-group size.
// CUDA backends launch global/local blocks of local threads.
struct NdRange {
  size_t global[3] = {1, 1, 1};
  size_t local[3] = {1, 1, 1};
  unsigned dimensions = 1;
  static NdRange linear(size_t global, size_t local) { return NdRange{{global, 1, 1}, {local, 1, 1}, 1}; }
};

class Queue {
 public:
  virtual ~Queue() = default;
  virtual const DeviceInfo& info() const = 0;
  // The backend API's objects behind this queue (compute/native_handles.hpp); none by default.
  virtual NativeHandles native_handles() const { return {}; }

  // Throws BackendError (naming the request and the device's limit) when the device cannot hold it.
  virtual std::unique_ptr<DeviceMemory> allocate(size_t bytes) = 0;
  // Blocking copies between host and device memory, at a byte offset into the device memory.
  virtual void write(DeviceMemory& memory, size_t offset, const void* source, size_t bytes) = 0;
  virtual void read(const DeviceMemory& memory, size_t offset, void* destination, size_t bytes) = 0;
  // A copy from the host enqueued in order with the work around it, not waited for: the bytes are taken
  // (staged) before it returns, so `source` may change at once. For a frame's input ahead of its
  // launches, where a blocking write would add the copy's round trip. By default the blocking write.
  virtual void write_enqueued(DeviceMemory& memory, size_t offset, const void* source, size_t bytes) {
    write(memory, offset, source, bytes);
  }
  // A copy to the host enqueued in order with the work around it, not waited for: the bytes reach
  // `destination` in wait_enqueued_reads(), which waits for that copy only, not for work enqueued after
  // it (a frame's estimate goes out ahead of the resampling only the next frame needs). `destination`
  // must stay valid until then. One read is in flight at a time: another first completes it. By
  // default the blocking read, at once.
  virtual void read_enqueued(const DeviceMemory& memory, size_t offset, void* destination, size_t bytes) {
    read(memory, offset, destination, bytes);
  }
  virtual void wait_enqueued_reads() {}
  // Host access to bytes [offset, offset + bytes) of `memory` for overwriting them all: a pointer
  // that stays valid until unmap(memory, pointer), which makes the new contents visible to work
  // enqueued after it. One mapping per queue at a time. OpenCL maps the buffer (no copy at all
  // where device memory is host memory, as on PoCL); CUDA writes a host staging area at unmap.
  virtual void* map_for_overwrite(DeviceMemory& memory, size_t offset, size_t bytes) = 0;
  virtual void unmap(DeviceMemory& memory, void* host) = 0;
  // Device-side copy between allocations.
  virtual void copy(const DeviceMemory& source, size_t source_offset, DeviceMemory& destination,
                    size_t destination_offset, size_t bytes) = 0;

  // Builds a program from OpenCL C source (cl/dt_prelude.h's words; each backend puts its own prelude,
  // src/compute/<name>/dt_prelude_<name>.h, before the source), with
  // -D definitions given as "NAME=VALUE" or "NAME". A failed build throws BackendError whose
  // message holds the device, the options and the compiler's log.
  virtual std::unique_ptr<Program> build(const std::string& name, const std::string& source,
                                         const std::vector<std::string>& definitions) = 0;
  // Enqueues a kernel with the arguments set so far; returns its event (timed on the device).
  virtual EventPtr launch(Kernel& kernel, const NdRange& range) = 0;
  // Sets args as the kernel's arguments 0, 1, ... in order, then enqueues it.
  template <class... Args>
  requires(sizeof...(Args) > 0) EventPtr launch(Kernel& kernel, const NdRange& range, const Args&... args) {
    set_launch_args(kernel, args...);
    return launch(kernel, range);
  }
  // Enqueues a kernel as launch() does but without an event: for the middle of a run of launches timed
  // by its first and last (Event::elapsed_since_ms), with no timing records on the device and less
  // host work per launch. Backends without a cheaper way launch with an event and drop it.
  virtual void launch_untimed(Kernel& kernel, const NdRange& range) { launch(kernel, range); }
  template <class... Args>
  requires(sizeof...(Args) > 0) void launch_untimed(Kernel& kernel, const NdRange& range, const Args&... args) {
    set_launch_args(kernel, args...);
    launch_untimed(kernel, range);
  }
  // Waits for everything enqueued.
  virtual void finish() = 0;

  // Launches from begin_batch() to end_batch() may be held back and handed to the device as one unit at
  // end_batch(), in order. CUDA makes them a graph and replays it, setting only the arguments that changed,
  // when the next batch launches the same kernels over the same ranges (a frame's ~27 launches become
  // one). The events of a batch's launches are valid until the queue's next batch is ended. Any other
  // queue operation inside a batch (a copy, finish) first hands over what was held. Backends without a
  // cheaper way launch at once (the default).
  virtual void begin_batch() {}
  virtual void end_batch() {}
  // Hands what the open batch holds so far to the device and goes on batching: the device starts on the
  // first launches while the host records the rest (a frame's latency). None open, or none held: nothing.
  virtual void flush_batch() {}

  // Another in-order queue on the same device and context: memory allocated and programs built through
  // either serve both, and work enqueued on the two may run at the same time (each tracker of several
  // gets one, so the objects' small kernels overlap). nullptr where a backend offers only one queue:
  // the caller then shares this one.
  virtual std::unique_ptr<Queue> another_queue() { return nullptr; }
};

// Queue::begin_batch() for a scope, ended by submit() or, on an exception, when the scope is left.
// launch() when `timed`, else launch_untimed() and no event (null): a launch whose device time only a
// profiling run reads (TrackerConfig::step_timings).
template <class... Args>
EventPtr launch_timed_if(bool timed, Queue& queue, Kernel& kernel, const NdRange& range, const Args&... args) {
  if constexpr (sizeof...(Args) > 0) set_launch_args(kernel, args...);
  if (timed) return queue.launch(kernel, range);
  queue.launch_untimed(kernel, range);
  return nullptr;
}

class LaunchBatch {
 public:
  LaunchBatch(Queue& queue, bool enabled) : queue_(enabled ? &queue : nullptr) {
    if (queue_) queue_->begin_batch();
  }
  ~LaunchBatch() {
    if (!queue_) return;
    try {
      queue_->end_batch();
    } catch (...) {  // already unwinding from the error that matters
    }
  }
  LaunchBatch(const LaunchBatch&) = delete;
  LaunchBatch& operator=(const LaunchBatch&) = delete;
  void submit() {
    Queue* queue = queue_;
    queue_ = nullptr;
    if (queue) queue->end_batch();
  }
  void flush() {
    if (queue_) queue_->flush_batch();
  }

 private:
  Queue* queue_;
};

// Devices of every backend compiled in (a backend whose runtime is absent lists none).
std::vector<DeviceInfo> list_devices();
// Opens the device a selection string names: "opencl" (the best device), "opencl:pocl",
// "opencl:nvidia" (a platform whose name contains the word), "opencl:<platform>.<device>",
// "cuda", "cuda:<n>". Unknown or absent: InputError that lists what is available.
std::unique_ptr<Queue> open_device(const std::string& selector);

}  // namespace depthtrack::compute
