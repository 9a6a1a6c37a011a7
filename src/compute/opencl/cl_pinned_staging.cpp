#include "compute/opencl/cl_pinned_staging.hpp"

#include <cstring>

#include "compute/format_bytes.hpp"
#include "compute/opencl/cl_errors.hpp"

namespace depthtrack::compute::opencl {

PinnedStaging::PinnedStaging(cl_context context, cl_command_queue queue, std::string device_name)
    : context_(context), queue_(queue), device_(std::move(device_name)) {}

PinnedStaging::~PinnedStaging() {
  // At teardown a failure has nowhere to go: the area must only outlive its last transfer.
  if (copying_) {
    const cl_event event = copied_.get();
    clWaitForEvents(1, &event);
  }
  // The buffer goes once the unmapping is done (its release waits for the commands that use it).
  if (host_) clEnqueueUnmapMemObject(queue_, area_.get(), host_, 0, nullptr, nullptr);
}

void PinnedStaging::wait_for_last_copy() {
  if (!copying_) return;
  const cl_event event = copied_.get();
  check(clWaitForEvents(1, &event), "clWaitForEvents", device_, "the last staged transfer");
  copying_ = false;
}

void PinnedStaging::release_area() {
  if (host_) {
    check(clEnqueueUnmapMemObject(queue_, area_.get(), host_, 0, nullptr, nullptr), "clEnqueueUnmapMemObject", device_,
          "a staging area");
  }
  host_ = nullptr;
  capacity_ = 0;
  area_ = MemHandle();
}

void PinnedStaging::reserve(size_t bytes) {
  if (bytes <= capacity_) return;
  release_area();
  const std::string request = "a staging area of " + format_bytes(bytes) + " in host memory";
  cl_int status = CL_SUCCESS;
  area_ = MemHandle(clCreateBuffer(context_, CL_MEM_READ_WRITE | CL_MEM_ALLOC_HOST_PTR, bytes, nullptr, &status));
  check(status, "clCreateBuffer", device_, request);
  host_ = clEnqueueMapBuffer(queue_, area_.get(), CL_TRUE, CL_MAP_READ | CL_MAP_WRITE, 0, bytes, 0, nullptr, nullptr,
                             &status);
  check(status, "clEnqueueMapBuffer", device_, request);
  capacity_ = bytes;
}

void PinnedStaging::copy_to_device(cl_mem destination, size_t offset, const void* source, size_t bytes) {
  wait_for_last_copy();
  reserve(bytes);
  std::memcpy(host_, source, bytes);
  cl_event event = nullptr;
  check(clEnqueueWriteBuffer(queue_, destination, CL_FALSE, offset, bytes, host_, 0, nullptr, &event),
        "clEnqueueWriteBuffer", device_);
  copied_ = EventHandle(event);
  copying_ = true;
}

void PinnedStaging::copy_to_host(void* destination, cl_mem source, size_t offset, size_t bytes) {
  deliver();
  wait_for_last_copy();
  reserve(bytes);
  cl_event event = nullptr;
  check(clEnqueueReadBuffer(queue_, source, CL_FALSE, offset, bytes, host_, 0, nullptr, &event), "clEnqueueReadBuffer",
        device_);
  copied_ = EventHandle(event);
  copying_ = true;
  destination_ = destination;
  pending_bytes_ = bytes;
}

void PinnedStaging::deliver() {
  if (!destination_) return;
  wait_for_last_copy();
  std::memcpy(destination_, host_, pending_bytes_);
  destination_ = nullptr;
  pending_bytes_ = 0;
}

}  // namespace depthtrack::compute::opencl
