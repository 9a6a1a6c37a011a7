#pragma once
// The CUDA Queue: one device's primary context and one in-order stream. Copies to and from the
// host block; launches and device copies are enqueued on the stream in order.
#include <memory>
#include <vector>

#include "compute/cuda/cuda_context.hpp"
#include "compute/cuda/cuda_launch_graph.hpp"
#include "compute/cuda/cuda_pinned_staging.hpp"
#include "compute/queue.hpp"

namespace depthtrack::compute::cuda {

class CudaMemory;

class CudaQueue final : public Queue {
 public:
  explicit CudaQueue(int ordinal);
  ~CudaQueue() override;
  CudaQueue(const CudaQueue&) = delete;
  CudaQueue& operator=(const CudaQueue&) = delete;

  const DeviceInfo& info() const override { return context_->info(); }
  NativeHandles native_handles() const override;
  std::unique_ptr<DeviceMemory> allocate(size_t bytes) override;
  void write(DeviceMemory& memory, size_t offset, const void* source, size_t bytes) override;
  void read(const DeviceMemory& memory, size_t offset, void* destination, size_t bytes) override;
  // Through page-locked staging, so the copy is a DMA the stream runs in order, not a driver-side
  // staging the host waits for.
  void write_enqueued(DeviceMemory& memory, size_t offset, const void* source, size_t bytes) override;
  // Through page-locked memory of its own, delivered at wait_enqueued_reads().
  void read_enqueued(const DeviceMemory& memory, size_t offset, void* destination, size_t bytes) override;
  void wait_enqueued_reads() override;
  void* map_for_overwrite(DeviceMemory& memory, size_t offset, size_t bytes) override;
  void unmap(DeviceMemory& memory, void* host) override;
  void copy(const DeviceMemory& source, size_t source_offset, DeviceMemory& destination, size_t destination_offset,
            size_t bytes) override;
  std::unique_ptr<Program> build(const std::string& name, const std::string& source,
                                 const std::vector<std::string>& definitions) override;
  EventPtr launch(Kernel& kernel, const NdRange& range) override;
  void launch_untimed(Kernel& kernel, const NdRange& range) override;
  void finish() override;
  // A batch becomes a CUDA graph (compute/cuda/cuda_launch_graph.hpp) where the driver has graphs and
  // DEPTHTRACK_CUDA_GRAPHS does not turn them off (compute/environment_switch.hpp; read when the queue is
  // made).
  void begin_batch() override;
  void end_batch() override;
  void flush_batch() override { hand_over_batch(); }
  const LaunchGraphs* graphs() const { return graphs_.get(); }  // null without graphs; for tests
  // A stream of its own in this queue's context, at the priority of the next rank there
  // (compute/cuda/cuda_stream.hpp: the queues made first run ahead).
  std::unique_ptr<Queue> another_queue() override;

  // For interop code that enqueues its own work in order with the queue's.
  const Context& context() const { return *context_; }
  CUstream stream() const { return stream_; }

 private:
  EventPtr enqueue(Kernel& kernel, const NdRange& range, bool timed);
  // Launches what a batch holds so far, so that the operation that follows keeps its place in order.
  void hand_over_batch();
  // A new stream in `context`, at the priority of the next queue rank there (Context::take_queue_rank).
  explicit CudaQueue(std::shared_ptr<const Context> context);

  CUdeviceptr write_target(DeviceMemory& memory, size_t offset, const void* source, size_t bytes);
  CUdeviceptr read_source(const DeviceMemory& memory, size_t offset, const void* destination, size_t bytes);
  // `memory` as this device's memory, with [offset, offset + bytes) inside it (else InputError).
  const CudaMemory& checked(const DeviceMemory& memory, size_t offset, size_t bytes, const char* what) const;

  std::shared_ptr<const Context> context_;
  CUstream stream_ = nullptr;
  std::unique_ptr<LaunchGraphs> graphs_;  // null where graphs are off
  std::unique_ptr<PinnedStaging> staging_;       // write_enqueued's, made at its first use
  std::unique_ptr<PinnedStaging> read_staging_;  // read_enqueued's, likewise
  bool upload_before_read_ = false;              // the last upload precedes the read in flight
  bool batching_ = false;
  // The one mapping map_for_overwrite hands out: host bytes written to the device at unmap.
  struct Mapping {
    DeviceMemory* memory = nullptr;
    size_t offset = 0;
    std::vector<unsigned char> host;
  } mapping_;
};

}  // namespace depthtrack::compute::cuda
