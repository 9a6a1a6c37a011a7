#pragma once
// Whether a Device opens the compute context of its GL trackers against its GL context
// (cl_khr_gl_sharing), decided from facts alone so that it is tested without such a platform: the
// Device's queue is OpenCL's, its device lists the extension, and GL is an EGL or GLX context.
// Otherwise the trackers run on the Device's own context and the reason says why.
#include <string>
#include <vector>

#include "atlas/gl/gl_native.hpp"

namespace depthtrack::interop {

struct SharedContextChoice {
  bool open_shared = false;
  std::string reason;  // why not; empty when open_shared
};

// opencl: the Device's queue holds an OpenCL context (NativeHandles::cl_context); device_extensions:
// CL_DEVICE_EXTENSIONS split into words (DeviceInfo::extensions).
SharedContextChoice choose_gl_shared_context(bool opencl, const std::vector<std::string>& device_extensions,
                                             const render::GlNativeContext& gl);

}  // namespace depthtrack::interop
