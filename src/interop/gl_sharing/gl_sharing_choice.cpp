#include "interop/gl_sharing/gl_sharing_choice.hpp"

#include <CL/cl_gl.h>

#include <depthtrack/error.hpp>

#include "interop/gl_shared_context_choice.hpp"

namespace depthtrack::interop {

namespace {
cl_context_properties display_property(render::GlNativeContext::Api api) {
  return api == render::GlNativeContext::Api::Egl ? CL_EGL_DISPLAY_KHR : CL_GLX_DISPLAY_KHR;
}

// The value of `name` in 0-terminated (name, value) pairs, or 0.
cl_context_properties property(std::span<const cl_context_properties> properties, cl_context_properties name) {
  for (size_t i = 0; i + 1 < properties.size() && properties[i] != 0; i += 2)
    if (properties[i] == name) return properties[i + 1];
  return 0;
}
}  // namespace

GlSharingChoice choose_gl_sharing(const std::vector<std::string>& device_extensions, const render::GlNativeContext& gl,
                                  std::span<const cl_context_properties> context_properties) {
  // The facts a Device decides by (listed, EGL or GLX), then that it did open the context against GL.
  if (const SharedContextChoice worth = choose_gl_shared_context(true, device_extensions, gl); !worth.open_shared)
    return {false, worth.reason};
  const auto shared_context = property(context_properties, CL_GL_CONTEXT_KHR);
  const auto shared_display = property(context_properties, display_property(gl.api));
  if (shared_context != reinterpret_cast<cl_context_properties>(gl.context) ||
      shared_display != reinterpret_cast<cl_context_properties>(gl.display))
    return {false,
            "cl_khr_gl_sharing is listed but the filter's OpenCL context was created before the GL context, "
            "not against it (open the queue with open_gl_shared_queue)"};
  return {true, ""};
}

std::vector<cl_context_properties> gl_sharing_properties(const render::GlNativeContext& gl) {
  if (gl.api == render::GlNativeContext::Api::None || !gl.context || !gl.display)
    throw InputError("cl_khr_gl_sharing needs an EGL or GLX context; this GL context (OSMesa) has no handles to share");
  return {CL_GL_CONTEXT_KHR, reinterpret_cast<cl_context_properties>(gl.context), display_property(gl.api),
          reinterpret_cast<cl_context_properties>(gl.display)};
}

}  // namespace depthtrack::interop
