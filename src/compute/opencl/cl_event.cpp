#include "compute/opencl/cl_event.hpp"

#include "compute/opencl/cl_errors.hpp"

namespace depthtrack::compute::opencl {

void ClEvent::wait() {
  const cl_event event = event_.get();
  check(clWaitForEvents(1, &event), "clWaitForEvents", device_);
}

double ClEvent::elapsed_ms() {
  wait();  // profiling counters are valid only once the command is complete
  cl_ulong start = 0, end = 0;
  check(clGetEventProfilingInfo(event_.get(), CL_PROFILING_COMMAND_START, sizeof start, &start, nullptr),
        "clGetEventProfilingInfo", device_);
  check(clGetEventProfilingInfo(event_.get(), CL_PROFILING_COMMAND_END, sizeof end, &end, nullptr),
        "clGetEventProfilingInfo", device_);
  return end >= start ? static_cast<double>(end - start) * 1e-6 : 0.0;  // nanoseconds
}

std::optional<double> ClEvent::elapsed_since_ms(Event& earlier) {
  auto* first = dynamic_cast<ClEvent*>(&earlier);
  if (!first || first->device_ != device_) return std::nullopt;
  wait();  // in order: the earlier command is complete too
  cl_ulong start = 0, end = 0;
  check(clGetEventProfilingInfo(first->event_.get(), CL_PROFILING_COMMAND_START, sizeof start, &start, nullptr),
        "clGetEventProfilingInfo", device_);
  check(clGetEventProfilingInfo(event_.get(), CL_PROFILING_COMMAND_END, sizeof end, &end, nullptr),
        "clGetEventProfilingInfo", device_);
  return end >= start ? static_cast<double>(end - start) * 1e-6 : 0.0;  // nanoseconds
}

}  // namespace depthtrack::compute::opencl
