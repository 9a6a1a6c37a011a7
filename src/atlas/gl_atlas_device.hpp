#pragma once
// What a tracker that draws its atlas with OpenGL (Renderer::Gl) runs on, as its Device hands it out
// (Device::gl_atlas): the Device's GL context, made once and shared by the GL trackers, and the compute
// context their filters run on. Where the device is OpenCL, lists cl_khr_gl_sharing and GL is EGL or GLX,
// that is an OpenCL context created against the GL context (the GL atlas is then used in place); else it is
// the Device's own. Free of GL and device headers, so the filter and tracker layers can pass it on.
#include <memory>
#include <string>

#include "compute/program_cache.hpp"

namespace depthtrack {

namespace render {
class GlContext;  // src/atlas/gl/gl_context.hpp
}

struct GlAtlasDevice {
  std::shared_ptr<render::GlContext> gl;
  // Opened against `gl` (with programs of its own: programs belong to one OpenCL context), or the Device's.
  std::shared_ptr<compute::DeviceContext> compute;
  // Why `compute` is the Device's own context although sharing was worth trying (the platform refused a
  // context against `gl`); the hand-off reports it. Empty otherwise.
  std::string shared_context_refused;
  bool shares_gl() const { return compute && compute->made_against != nullptr; }
};

// Makes the GL context for `device` (on its GPU where EGL can tell; on `gl_path` alone unless "auto") and,
// where choose_gl_shared_context (src/interop/gl_shared_context_choice.hpp) says so, opens the compute
// context against it; a refusal falls back to `device`, saying why. BackendError naming every GL path tried
// when no GL context can be made; InputError for a bad gl_path or a build without GL.
GlAtlasDevice open_gl_atlas_device(const std::shared_ptr<compute::DeviceContext>& device, const std::string& gl_path);

}  // namespace depthtrack
