#pragma once
// When the cl_khr_gl_sharing hand-off can be used, decided from facts alone (so that it is tested
// without such a platform): the device must list the extension, GL must be an EGL or GLX context,
// and the OpenCL context must have been created against that GL context (CL_GL_CONTEXT_KHR plus
// CL_EGL_DISPLAY_KHR or CL_GLX_DISPLAY_KHR). Otherwise the reason says which is missing.
#include <CL/cl.h>

#include <span>
#include <string>
#include <vector>

#include "atlas/gl/gl_native.hpp"

namespace depthtrack::interop {

struct GlSharingChoice {
  bool share = false;
  std::string reason;  // why not; empty when share
};

// device_extensions: CL_DEVICE_EXTENSIONS split into words (DeviceInfo::extensions);
// context_properties: the queue's CL_CONTEXT_PROPERTIES, 0-terminated (name, value) pairs.
GlSharingChoice choose_gl_sharing(const std::vector<std::string>& device_extensions, const render::GlNativeContext& gl,
                                  std::span<const cl_context_properties> context_properties);

// The (name, value) pairs clCreateContext needs after CL_CONTEXT_PLATFORM to share `gl`, without
// the terminating 0; InputError for a context without native handles (OSMesa).
std::vector<cl_context_properties> gl_sharing_properties(const render::GlNativeContext& gl);

}  // namespace depthtrack::interop
