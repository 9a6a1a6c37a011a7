// Picks the hand-off per platform, best first, and keeps the reason each better one was passed over. The
// choice is by capability: which API's objects the queue's native handles hold, and what the device and GL
// context offer; no backend is named.
#include "interop/atlas_handoff.hpp"

namespace depthtrack::interop {

// The paths a build leaves out (src/CMakeLists.txt builds interop/cuda with CUDA, interop/opencl with both).
#ifndef DEPTHTRACK_WITH_CUDA
std::unique_ptr<AtlasHandoff> make_cuda_gl_handoff(compute::Queue&, render::AtlasRenderer&, std::string& why_not) {
  why_not = "built without the CUDA backend";
  return nullptr;
}
#endif
#if !defined(DEPTHTRACK_WITH_CUDA) || !defined(DEPTHTRACK_WITH_OPENCL)
std::unique_ptr<AtlasHandoff> make_opencl_gl_bridge_handoff(compute::Queue&, render::AtlasRenderer&,
                                                            std::string& why_not) {
  why_not = "the GL-OpenCL bridge needs both the OpenCL and the CUDA backend (its memory is allocated by CUDA)";
  return nullptr;
}
#endif
#ifndef DEPTHTRACK_WITH_OPENCL
std::unique_ptr<AtlasHandoff> make_cl_gl_sharing_handoff(compute::Queue&, render::AtlasRenderer&,
                                                         std::string& why_not) {
  why_not = "built without the OpenCL backend";
  return nullptr;
}
#endif

std::unique_ptr<AtlasHandoff> make_atlas_handoff(compute::Queue& queue, render::AtlasRenderer& renderer,
                                                 const std::string& shared_context_refused) {
  const compute::DeviceInfo& device = queue.info();
  const compute::NativeHandles native = queue.native_handles();
  std::string reason;
  if (native.cu_context) {
    if (auto cuda = make_cuda_gl_handoff(queue, renderer, reason)) return cuda;
    reason = "no CUDA-GL interop: " + reason;
  } else if (!native.cl_context) {
    reason = "the " + device.backend + " device offers no CUDA or OpenCL objects to share with GL";
  } else if (!device.gl_sharing) {
    std::string bridge;
    if (device.external_memory) {
      if (auto bridged = make_opencl_gl_bridge_handoff(queue, renderer, bridge)) return bridged;
      bridge = "; no GL-OpenCL bridge: " + bridge;
    }
    reason = "the OpenCL platform lacks cl_khr_gl_sharing" + bridge;
  } else {
    // Sharing needs the OpenCL context created against the GL context (gl_sharing/gl_shared_queue.hpp).
    if (auto shared = make_cl_gl_sharing_handoff(queue, renderer, reason)) return shared;
    if (!shared_context_refused.empty()) reason = shared_context_refused;
  }
  return make_staged_handoff(queue, renderer, reason);
}

}  // namespace depthtrack::interop
