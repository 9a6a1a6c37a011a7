#include "compute/opencl/cl_queue.hpp"

#include <cstdio>
#include <cstring>
#include <depthtrack/error.hpp>

#include "compute/format_bytes.hpp"
#include "compute/opencl/cl_cached_build.hpp"
#include "compute/opencl/cl_errors.hpp"
#include "compute/opencl/cl_event.hpp"
#include "compute/opencl/cl_kernel.hpp"
#include "compute/opencl/cl_memory.hpp"
#include "compute/opencl/cl_program.hpp"

namespace depthtrack::compute::opencl {

namespace {
using depthtrack::compute::format_bytes;

void check_range(const char* what, size_t offset, size_t bytes, const DeviceMemory& memory) {
  if (offset > memory.bytes() || bytes > memory.bytes() - offset)
    throw InputError(std::string(what) + " of bytes [" + std::to_string(offset) + ", " +
                     std::to_string(offset + bytes) + ") is outside a device buffer of " +
                     std::to_string(memory.bytes()) + " bytes");
}

// A transfer's checks, shared by the blocking and enqueued writes (to_device) and reads: the range inside
// the buffer and a host pointer; false when there is nothing to copy (OpenCL 1.2 rejects empty transfers).
bool transfer_wanted(bool to_device, size_t offset, size_t bytes, const DeviceMemory& memory, const void* host) {
  const char* what = to_device ? "write" : "read";
  check_range(what, offset, bytes, memory);
  if (bytes == 0) return false;
  if (!host)
    throw InputError(std::string(what) + " of " + std::to_string(bytes) + " bytes " + (to_device ? "from" : "into") +
                     " a null host pointer");
  return true;
}

std::string sizes(const size_t* values, unsigned dimensions) {
  std::string text = "[";
  for (unsigned d = 0; d < dimensions; ++d) text += (d ? ", " : "") + std::to_string(values[d]);
  return text + "]";
}
}  // namespace

ClQueue::ClQueue(cl_platform_id platform, cl_device_id device, DeviceInfo info,
                 const std::vector<cl_context_properties>& extra_properties)
    : device_(device), info_(std::move(info)) {
  std::vector<cl_context_properties> properties = {CL_CONTEXT_PLATFORM,
                                                   reinterpret_cast<cl_context_properties>(platform)};
  properties.insert(properties.end(), extra_properties.begin(), extra_properties.end());
  properties.push_back(0);
  cl_int status = CL_SUCCESS;
  // No notification callback: every error it would print also comes back from the failing call.
  context_ = ContextHandle(clCreateContext(properties.data(), 1, &device_, nullptr, nullptr, &status));
  check(status, "clCreateContext", info_.name);
  create_queue();
}

ClQueue::ClQueue(cl_context context, cl_device_id device, DeviceInfo info) : device_(device), info_(std::move(info)) {
  check(clRetainContext(context), "clRetainContext", info_.name);
  context_ = ContextHandle(context);
  create_queue();
}

void ClQueue::create_queue() {
  cl_int status = CL_SUCCESS;
  queue_ = QueueHandle(clCreateCommandQueue(context_.get(), device_, CL_QUEUE_PROFILING_ENABLE, &status));
  check(status, "clCreateCommandQueue", info_.name);
}

std::unique_ptr<Queue> ClQueue::another_queue() {
  return std::unique_ptr<Queue>(new ClQueue(context_.get(), device_, info_));
}

std::unique_ptr<DeviceMemory> ClQueue::allocate(size_t bytes) {
  // Refused here rather than by the driver, whose CL_INVALID_BUFFER_SIZE names neither number.
  if (bytes == 0)
    throw BackendError("cannot allocate 0 bytes on " + info_.name + ": a device buffer needs at least one byte");
  if (bytes > info_.max_allocation)
    throw BackendError("cannot allocate " + format_bytes(bytes) + " (" + std::to_string(bytes) + " bytes) on " +
                       info_.name + ": the device allows at most " + format_bytes(info_.max_allocation) + " (" +
                       std::to_string(info_.max_allocation) + " bytes) in one buffer");
  cl_int status = CL_SUCCESS;
  MemHandle buffer(clCreateBuffer(context_.get(), CL_MEM_READ_WRITE, bytes, nullptr, &status));
  const std::string request =
      "a buffer of " + format_bytes(bytes) + " (global memory " + format_bytes(info_.global_memory) + ")";
  check(status, "clCreateBuffer", info_.name, request);
  // Drivers back buffers lazily; touching one byte makes an out-of-memory surface here, not at a later launch.
  const unsigned char zero = 0;
  check(clEnqueueWriteBuffer(queue_.get(), buffer.get(), CL_TRUE, 0, 1, &zero, 0, nullptr, nullptr),
        "clEnqueueWriteBuffer", info_.name, request);
  return std::make_unique<ClMemory>(std::move(buffer), bytes);
}

void ClQueue::write(DeviceMemory& memory, size_t offset, const void* source, size_t bytes) {
  if (!transfer_wanted(true, offset, bytes, memory, source)) return;
  check(clEnqueueWriteBuffer(queue_.get(), cl_buffer(memory, "write"), CL_TRUE, offset, bytes, source, 0, nullptr,
                             nullptr),
        "clEnqueueWriteBuffer", info_.name);
}

ClQueue::~ClQueue() {
  staging_.reset();  // each waits for its last transfer
  read_staging_.reset();
}

void ClQueue::write_enqueued(DeviceMemory& memory, size_t offset, const void* source, size_t bytes) {
  if (!transfer_wanted(true, offset, bytes, memory, source)) return;
  if (!staging_) staging_ = std::make_unique<PinnedStaging>(context_.get(), queue_.get(), info_.name);
  staging_->copy_to_device(cl_buffer(memory, "write"), offset, source, bytes);
}

void ClQueue::read_enqueued(const DeviceMemory& memory, size_t offset, void* destination, size_t bytes) {
  if (!transfer_wanted(false, offset, bytes, memory, destination)) return;
  wait_enqueued_reads();
  if (!read_staging_) read_staging_ = std::make_unique<PinnedStaging>(context_.get(), queue_.get(), info_.name);
  read_staging_->copy_to_host(destination, cl_buffer(memory, "read"), offset, bytes);
  upload_before_read_ = staging_ && staging_->copy_pending();
}

void ClQueue::wait_enqueued_reads() {
  if (!read_staging_) return;
  read_staging_->deliver();
  // The queue is in order: a write enqueued before the read is done too.
  if (upload_before_read_) staging_->copy_known_done();
  upload_before_read_ = false;
}

void ClQueue::read(const DeviceMemory& memory, size_t offset, void* destination, size_t bytes) {
  if (!transfer_wanted(false, offset, bytes, memory, destination)) return;
  check(clEnqueueReadBuffer(queue_.get(), cl_buffer(memory, "read"), CL_TRUE, offset, bytes, destination, 0, nullptr,
                            nullptr),
        "clEnqueueReadBuffer", info_.name);
}

void* ClQueue::map_for_overwrite(DeviceMemory& memory, size_t offset, size_t bytes) {
  check_range("map", offset, bytes, memory);
  if (mapped_) throw InputError("map on " + info_.name + ": another range is still mapped");
  cl_int status = CL_SUCCESS;
  void* host = clEnqueueMapBuffer(queue_.get(), cl_buffer(memory, "map"), CL_TRUE, CL_MAP_WRITE_INVALIDATE_REGION,
                                  offset, bytes, 0, nullptr, nullptr, &status);
  check(status, "clEnqueueMapBuffer", info_.name, std::to_string(bytes) + " bytes");
  mapped_ = &memory;
  return host;
}

void ClQueue::unmap(DeviceMemory& memory, void* host) {
  if (mapped_ != &memory) throw InputError("unmap on " + info_.name + ": that buffer is not mapped");
  mapped_ = nullptr;
  check(clEnqueueUnmapMemObject(queue_.get(), cl_buffer(memory, "unmap"), host, 0, nullptr, nullptr),
        "clEnqueueUnmapMemObject", info_.name);
}

void ClQueue::copy(const DeviceMemory& source, size_t source_offset, DeviceMemory& destination,
                   size_t destination_offset, size_t bytes) {
  check_range("copy source", source_offset, bytes, source);
  check_range("copy destination", destination_offset, bytes, destination);
  if (bytes == 0) return;
  const bool overlap = &source == &destination && source_offset < destination_offset + bytes &&
                       destination_offset < source_offset + bytes;
  if (overlap) throw InputError("copy within one buffer with overlapping source and destination ranges");
  check(clEnqueueCopyBuffer(queue_.get(), cl_buffer(source, "copy"), cl_buffer(destination, "copy"), source_offset,
                            destination_offset, bytes, 0, nullptr, nullptr),
        "clEnqueueCopyBuffer", info_.name);
}

NativeHandles ClQueue::native_handles() const {
  NativeHandles handles;
  handles.cl_context = context_.get();
  handles.cl_device = device_;
  handles.cl_queue = queue_.get();
  return handles;
}

std::unique_ptr<Program> ClQueue::build(const std::string& name, const std::string& source,
                                        const std::vector<std::string>& definitions) {
  // The environment is read per build, so a test (or a program) can point it elsewhere or turn it off.
  return build_cached(ProgramBinaryCache::from_environment(), context_.get(), device_, info_, name, source,
                      definitions);
}

EventPtr ClQueue::launch(Kernel& kernel, const NdRange& range) {
  return enqueue(kernel, range, true);
}

void ClQueue::launch_untimed(Kernel& kernel, const NdRange& range) {
  enqueue(kernel, range, false);
}

// The launch, with an event when timed (else nullptr).
EventPtr ClQueue::enqueue(Kernel& kernel, const NdRange& range, bool timed) {
  auto* cl = dynamic_cast<ClKernel*>(&kernel);
  if (!cl) throw InputError("launch of kernel '" + kernel.name() + "': it was not built by an OpenCL queue");
  // Described only for an error: a frame launches some 30 kernels, and the text is a few allocations each.
  const auto what = [&] {
    return "kernel '" + kernel.name() + "' over global " + sizes(range.global, range.dimensions) + ", local " +
           sizes(range.local, range.dimensions);
  };
  if (range.dimensions < 1 || range.dimensions > 3)
    throw InputError("launch of kernel '" + kernel.name() + "' in " + std::to_string(range.dimensions) +
                     " dimensions: give 1, 2 or 3");
  size_t group = 1;
  for (unsigned d = 0; d < range.dimensions; ++d) {
    if (range.global[d] == 0 || range.local[d] == 0 || range.global[d] % range.local[d] != 0)
      throw InputError("launch of " + what() + ": every global size must be a positive multiple of the local size");
    group *= range.local[d];
  }
  if (group > info_.max_work_group_size)
    throw InputError("launch of " + what() + ": a work-group of " + std::to_string(group) +
                     " work-items is more than the device's " + std::to_string(info_.max_work_group_size));
  cl_event event = nullptr;
  const cl_int status = clEnqueueNDRangeKernel(queue_.get(), cl->get(), range.dimensions, nullptr, range.global,
                                               range.local, 0, nullptr, timed ? &event : nullptr);
  if (status != CL_SUCCESS) check(status, "clEnqueueNDRangeKernel", info_.name, what());
  return timed ? std::make_shared<ClEvent>(EventHandle(event), info_.name) : nullptr;
}

void ClQueue::flush_batch() {
  check(clFlush(queue_.get()), "clFlush", info_.name);
}

void ClQueue::finish() {
  check(clFinish(queue_.get()), "clFinish", info_.name);
  if (staging_) staging_->copy_known_done();
}

}  // namespace depthtrack::compute::opencl
