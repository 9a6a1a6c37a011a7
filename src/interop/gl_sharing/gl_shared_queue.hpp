#pragma once
// An OpenCL queue whose context is created against a GL context (cl_khr_gl_sharing), so that the
// GL atlas' textures can be used by OpenCL without a copy through the host. The tracker's own
// queue is opened before GL, so this is the way to a sharing queue.
#include <memory>

#include "atlas/gl/gl_context.hpp"
#include "compute/device_info.hpp"
#include "compute/queue.hpp"

namespace depthtrack::interop {

// `device` is an OpenCL device (DeviceInfo::selector "opencl:P.D") that lists cl_khr_gl_sharing,
// `gl` an EGL context on the same GPU. BackendError saying which of these fails (the device lacks
// the extension, OSMesa, the platform refuses the context or says it is not on this device).
std::unique_ptr<compute::Queue> open_gl_shared_queue(const compute::DeviceInfo& device, const render::GlContext& gl);

}  // namespace depthtrack::interop
