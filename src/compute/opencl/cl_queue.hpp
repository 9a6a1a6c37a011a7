#pragma once
// One OpenCL device as Queue: its own context and an in-order, profiled command queue.
#include <CL/cl.h>

#include <memory>
#include <vector>

#include "compute/opencl/cl_handle.hpp"
#include "compute/opencl/cl_pinned_staging.hpp"
#include "compute/queue.hpp"

namespace depthtrack::compute::opencl {

class ClQueue final : public Queue {
 public:
  // extra_properties: (name, value) pairs clCreateContext gets after the platform's, e.g. the GL
  // context and display of cl_khr_gl_sharing.
  ClQueue(cl_platform_id platform, cl_device_id device, DeviceInfo info,
          const std::vector<cl_context_properties>& extra_properties = {});

  const DeviceInfo& info() const override { return info_; }
  NativeHandles native_handles() const override;
  std::unique_ptr<DeviceMemory> allocate(size_t bytes) override;
  void write(DeviceMemory& memory, size_t offset, const void* source, size_t bytes) override;
  void read(const DeviceMemory& memory, size_t offset, void* destination, size_t bytes) override;
  // A non-blocking write through pinned host memory (PinnedStaging).
  void write_enqueued(DeviceMemory& memory, size_t offset, const void* source, size_t bytes) override;
  // A non-blocking read into pinned host memory, delivered at wait_enqueued_reads().
  void read_enqueued(const DeviceMemory& memory, size_t offset, void* destination, size_t bytes) override;
  void wait_enqueued_reads() override;
  ~ClQueue() override;
  void* map_for_overwrite(DeviceMemory& memory, size_t offset, size_t bytes) override;
  void unmap(DeviceMemory& memory, void* host) override;
  void copy(const DeviceMemory& source, size_t source_offset, DeviceMemory& destination, size_t destination_offset,
            size_t bytes) override;
  std::unique_ptr<Program> build(const std::string& name, const std::string& source,
                                 const std::vector<std::string>& definitions) override;
  EventPtr launch(Kernel& kernel, const NdRange& range) override;
  void launch_untimed(Kernel& kernel, const NdRange& range) override;
  void finish() override;
  // Submits what is enqueued (clFlush): the device starts on a frame's first launches while the host
  // enqueues the rest.
  void flush_batch() override;
  // A command queue of its own on this queue's context.
  std::unique_ptr<Queue> another_queue() override;

  // For interop code that enqueues its own work in order with the queue's.
  cl_context context() const { return context_.get(); }
  cl_command_queue queue() const { return queue_.get(); }
  cl_device_id device() const { return device_; }

 private:
  EventPtr enqueue(Kernel& kernel, const NdRange& range, bool timed);
  // A new command queue on `context` (retained here).
  ClQueue(cl_context context, cl_device_id device, DeviceInfo info);
  void create_queue();

  cl_device_id device_;
  DeviceInfo info_;
  ContextHandle context_;
  QueueHandle queue_;
  const DeviceMemory* mapped_ = nullptr;  // the one mapping map_for_overwrite hands out
  // write_enqueued's and read_enqueued's areas, made at first use; after the queue, so that they go
  // (waiting for their last transfer) while it still exists.
  std::unique_ptr<PinnedStaging> staging_, read_staging_;
  bool upload_before_read_ = false;  // a write was pending when the read was enqueued: done once it is
};

}  // namespace depthtrack::compute::opencl
