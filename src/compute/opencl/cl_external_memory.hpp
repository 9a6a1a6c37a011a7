#pragma once
// Memory another API allocated and exported as an opaque POSIX fd, imported into an OpenCL queue's
// context (cl_khr_external_memory_opaque_fd). Work that touches it must sit between acquire and
// release on the queue.
#include <memory>

#include "compute/queue.hpp"

namespace depthtrack::compute::opencl {

// BackendError naming the call and the code when the platform refuses the handle. The fd stays the
// caller's (the extension leaves open whether the import takes it, so a duplicate is imported).
std::unique_ptr<DeviceMemory> import_opaque_fd(Queue& queue, int fd, size_t bytes);
void acquire_external(Queue& queue, const DeviceMemory& memory);
void release_external(Queue& queue, const DeviceMemory& memory);

}  // namespace depthtrack::compute::opencl
