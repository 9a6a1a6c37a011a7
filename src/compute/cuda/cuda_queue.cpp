#include "compute/cuda/cuda_queue.hpp"

#include <depthtrack/error.hpp>

#include "compute/cuda/cuda_cached_build.hpp"
#include "compute/cuda/cuda_event.hpp"
#include "compute/cuda/cuda_kernel.hpp"
#include "compute/cuda/cuda_memory.hpp"
#include "compute/cuda/cuda_module.hpp"
#include "compute/cuda/cuda_program.hpp"
#include "compute/cuda/cuda_stream.hpp"
#include "compute/environment_switch.hpp"

namespace depthtrack::compute::cuda {

CudaQueue::CudaQueue(int ordinal) : CudaQueue(std::make_shared<const Context>(ordinal)) {}

CudaQueue::CudaQueue(std::shared_ptr<const Context> context) : context_(std::move(context)) {
  context_->make_current();
  stream_ = create_ranked_stream(*context_, context_->take_queue_rank());
  if (!turned_off_by_environment("DEPTHTRACK_CUDA_GRAPHS") && LaunchGraphs::supported(context_->api()))
    graphs_ = std::make_unique<LaunchGraphs>(context_);
}

CudaQueue::~CudaQueue() {
  graphs_.reset();
  staging_.reset();  // each waits for its last copy
  read_staging_.reset();
  // Pending work still completes; the driver frees the stream afterwards.
  if (context_->try_make_current()) context_->api().cuStreamDestroy(stream_);
}

void CudaQueue::begin_batch() {
  if (batching_) throw InputError("begin_batch on " + context_->where() + ": a batch is already open");
  batching_ = graphs_ != nullptr;
  if (graphs_) graphs_->begin_batch();
}

void CudaQueue::end_batch() {
  if (!batching_) return;
  batching_ = false;
  graphs_->submit(stream_);
}

void CudaQueue::hand_over_batch() {
  if (batching_) graphs_->submit(stream_);
}

std::unique_ptr<DeviceMemory> CudaQueue::allocate(size_t bytes) {
  return std::make_unique<CudaMemory>(context_, bytes);
}

const CudaMemory& CudaQueue::checked(const DeviceMemory& memory, size_t offset, size_t bytes, const char* what) const {
  // A pointer, not a reference: GCC 13 takes a reference bound to a call with a string argument
  // for a dangling one (-Wdangling-reference).
  const CudaMemory* cuda = &cuda_memory(memory, *context_, what);
  if (offset > cuda->bytes() || bytes > cuda->bytes() - offset)
    throw InputError(std::string(what) + " of bytes [" + std::to_string(offset) + ", " +
                     std::to_string(offset + bytes) + ") is outside an allocation of " + std::to_string(cuda->bytes()) +
                     " bytes on " + context_->where());
  return *cuda;
}

// Where a write of `bytes` from `source` goes on the device, checked, with the batch handed over and the
// context current; 0 when there is nothing to write.
CUdeviceptr CudaQueue::write_target(DeviceMemory& memory, size_t offset, const void* source, size_t bytes) {
  const CudaMemory& cuda = checked(memory, offset, bytes, "write");
  if (bytes == 0) return 0;
  if (!source) throw InputError("write of " + std::to_string(bytes) + " bytes from a null host pointer");
  hand_over_batch();
  context_->make_current();
  return cuda.pointer() + offset;
}

void CudaQueue::write(DeviceMemory& memory, size_t offset, const void* source, size_t bytes) {
  const CUdeviceptr target = write_target(memory, offset, source, bytes);
  if (!target) return;
  // On the queue's stream, then waited for: in order with enqueued work, and blocking.
  context_->check(context_->api().cuMemcpyHtoDAsync(target, source, bytes, stream_), "cuMemcpyHtoDAsync");
  finish();
}

void CudaQueue::write_enqueued(DeviceMemory& memory, size_t offset, const void* source, size_t bytes) {
  const CUdeviceptr target = write_target(memory, offset, source, bytes);
  if (!target) return;
  if (!staging_) staging_ = std::make_unique<PinnedStaging>(context_);
  staging_->copy_to_device(target, source, bytes, stream_);
  upload_before_read_ = false;  // this copy follows any read in flight
}

// Where a read of `bytes` into `destination` comes from on the device, checked, with the batch handed
// over and the context current; 0 when there is nothing to read.
CUdeviceptr CudaQueue::read_source(const DeviceMemory& memory, size_t offset, const void* destination, size_t bytes) {
  const CudaMemory& cuda = checked(memory, offset, bytes, "read");
  if (bytes == 0) return 0;
  if (!destination) throw InputError("read of " + std::to_string(bytes) + " bytes into a null host pointer");
  hand_over_batch();
  context_->make_current();
  return cuda.pointer() + offset;
}

void CudaQueue::read_enqueued(const DeviceMemory& memory, size_t offset, void* destination, size_t bytes) {
  const CUdeviceptr source = read_source(memory, offset, destination, bytes);
  if (!source) return;
  if (!read_staging_) read_staging_ = std::make_unique<PinnedStaging>(context_);
  read_staging_->copy_to_host(destination, source, bytes, stream_);
  upload_before_read_ = staging_ && staging_->copy_pending();
}

void CudaQueue::wait_enqueued_reads() {
  if (!read_staging_) return;
  read_staging_->deliver();
  // The stream runs in order: the upload enqueued before the read is done too.
  if (upload_before_read_) staging_->copy_known_done();
  upload_before_read_ = false;
}

void CudaQueue::read(const DeviceMemory& memory, size_t offset, void* destination, size_t bytes) {
  const CUdeviceptr source = read_source(memory, offset, destination, bytes);
  if (!source) return;
  context_->check(context_->api().cuMemcpyDtoHAsync(destination, source, bytes, stream_), "cuMemcpyDtoHAsync");
  finish();
}

void* CudaQueue::map_for_overwrite(DeviceMemory& memory, size_t offset, size_t bytes) {
  checked(memory, offset, bytes, "map");
  if (mapping_.memory) throw InputError("map on " + context_->where() + ": another range is still mapped");
  mapping_.memory = &memory;
  mapping_.offset = offset;
  mapping_.host.resize(bytes);
  return mapping_.host.data();
}

void CudaQueue::unmap(DeviceMemory& memory, void* host) {
  if (mapping_.memory != &memory || host != mapping_.host.data())
    throw InputError("unmap on " + context_->where() + ": that range is not mapped");
  mapping_.memory = nullptr;
  write(memory, mapping_.offset, host, mapping_.host.size());
}

void CudaQueue::copy(const DeviceMemory& source, size_t source_offset, DeviceMemory& destination,
                     size_t destination_offset, size_t bytes) {
  const CudaMemory& from = checked(source, source_offset, bytes, "copy source");
  const CudaMemory& to = checked(destination, destination_offset, bytes, "copy destination");
  if (bytes == 0) return;
  // The driver does not define overlapping copies (OpenCL refuses them: CL_MEM_COPY_OVERLAP).
  const CUdeviceptr from_start = from.pointer() + source_offset, to_start = to.pointer() + destination_offset;
  if (from_start < to_start + bytes && to_start < from_start + bytes)
    throw InputError("copy of " + std::to_string(bytes) + " bytes from offset " + std::to_string(source_offset) +
                     " to offset " + std::to_string(destination_offset) + " of one allocation: the ranges overlap");
  hand_over_batch();
  context_->make_current();
  context_->check(context_->api().cuMemcpyDtoDAsync(to.pointer() + destination_offset, from.pointer() + source_offset,
                                                    bytes, stream_),
                  "cuMemcpyDtoDAsync");
}

NativeHandles CudaQueue::native_handles() const {
  NativeHandles handles;
  handles.cu_context = context_->get();
  handles.cu_stream = stream_;
  handles.cu_device = context_->device();
  return handles;
}

std::unique_ptr<Program> CudaQueue::build(const std::string& name, const std::string& source,
                                          const std::vector<std::string>& definitions) {
  // The environment is read per build, so a test (or a program) can point it elsewhere or turn it off.
  return build_cached(ProgramBinaryCache::from_environment(), context_, name, source, definitions);
}

EventPtr CudaQueue::launch(Kernel& kernel, const NdRange& range) {
  return enqueue(kernel, range, true);
}

void CudaQueue::launch_untimed(Kernel& kernel, const NdRange& range) {
  enqueue(kernel, range, false);
}

// The launch, between a timing event's two records when timed (else no event: nullptr).
EventPtr CudaQueue::enqueue(Kernel& kernel, const NdRange& range, bool timed) {
  auto* cuda = dynamic_cast<CudaKernel*>(&kernel);
  if (!cuda)
    throw InputError("launch on " + context_->where() + ": kernel '" + kernel.name() + "' is not a CUDA kernel");
  if (cuda->context().device() != context_->device())
    throw InputError("launch on " + context_->where() + ": kernel '" + kernel.name() + "' was built for " +
                     cuda->context().where());
  const LaunchShape shape = launch_shape(range, cuda->limits(), cuda->name(), context_->where());
  if (batching_) return graphs_->record(*cuda, shape, timed);
  std::vector<void*> arguments = cuda->argument_pointers();
  context_->make_current();
  std::shared_ptr<CudaEvent> event = timed ? std::make_shared<CudaEvent>(context_) : nullptr;
  if (event) event->record_start(stream_);
  // No dynamic shared memory: kernels declare fixed-size __local arrays.
  const CUresult status =
      context_->api().cuLaunchKernel(cuda->function(), shape.grid[0], shape.grid[1], shape.grid[2], shape.block[0],
                                     shape.block[1], shape.block[2], 0, stream_, arguments.data(), nullptr);
  if (status != CUDA_SUCCESS) {
    const auto dims = [](const unsigned(&v)[3]) {
      return std::to_string(v[0]) + "x" + std::to_string(v[1]) + "x" + std::to_string(v[2]);
    };
    const std::string call =
        "cuLaunchKernel of '" + cuda->name() + "' (grid " + dims(shape.grid) + ", block " + dims(shape.block) + ")";
    context_->check(status, call.c_str());
  }
  if (event) event->record_end(stream_);
  return event;
}

std::unique_ptr<Queue> CudaQueue::another_queue() {
  return std::unique_ptr<Queue>(new CudaQueue(context_));
}

void CudaQueue::finish() {
  hand_over_batch();
  context_->make_current();
  context_->check(context_->api().cuStreamSynchronize(stream_), "cuStreamSynchronize");
  if (staging_) staging_->copy_known_done();
  upload_before_read_ = false;
}

}  // namespace depthtrack::compute::cuda
