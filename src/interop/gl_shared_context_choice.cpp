#include "interop/gl_shared_context_choice.hpp"

#include <algorithm>

namespace depthtrack::interop {

SharedContextChoice choose_gl_shared_context(bool opencl, const std::vector<std::string>& device_extensions,
                                             const render::GlNativeContext& gl) {
  if (!opencl) return {false, "the device is not OpenCL's (cl_khr_gl_sharing is an OpenCL extension)"};
  if (std::find(device_extensions.begin(), device_extensions.end(), "cl_khr_gl_sharing") == device_extensions.end())
    return {false, "the OpenCL platform lacks cl_khr_gl_sharing"};
  if (gl.api == render::GlNativeContext::Api::None || !gl.context || !gl.display)
    return {false,
            "cl_khr_gl_sharing is listed but the GL context is OSMesa's, which OpenCL cannot share (only EGL "
            "and GLX contexts)"};
  return {true, ""};
}

}  // namespace depthtrack::interop
