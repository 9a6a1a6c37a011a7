// A Device's GL side: the GL context first, then, where sharing is worth trying, an OpenCL context
// created against it (cl_khr_gl_sharing needs the OpenCL context made that way; the Device's own was
// opened before any GL existed). A platform that refuses leaves the trackers on the Device's own context.
#include <depthtrack/error.hpp>

#include "atlas/gl/gl_context.hpp"
#include "atlas/gl_atlas_device.hpp"
#include "interop/gl_shared_context_choice.hpp"
#ifdef DEPTHTRACK_WITH_OPENCL
#include "interop/gl_sharing/gl_shared_queue.hpp"
#endif

namespace depthtrack {

GlAtlasDevice open_gl_atlas_device(const std::shared_ptr<compute::DeviceContext>& device, const std::string& gl_path) {
  const compute::DeviceInfo& info = device->queue->info();
  auto gl = std::make_shared<render::GlContext>(render::GlContextOptions::for_device(info.uuid, gl_path));
  const interop::SharedContextChoice choice = interop::choose_gl_shared_context(
      device->queue->native_handles().cl_context != nullptr, info.extensions, gl->native());
  if (!choice.open_shared) return {gl, device, ""};
#ifdef DEPTHTRACK_WITH_OPENCL
  try {
    auto shared = std::make_shared<compute::DeviceContext>(interop::open_gl_shared_queue(info, *gl), gl);
    return {gl, std::move(shared), ""};
  } catch (const Error& e) {
    return {gl, device,
            "cl_khr_gl_sharing is listed but the platform refused an OpenCL context against the GL context (" +
                std::string(e.what()) + "), so the filter runs on the Device's own context"};
  }
#else
  return {gl, device, "cl_khr_gl_sharing is listed but this build has no OpenCL backend"};
#endif
}

}  // namespace depthtrack
