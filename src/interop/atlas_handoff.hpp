#pragma once
// How particle poses reach the GL atlas renderer and its pages reach the compute kernels. Chosen
// per platform (make_atlas_handoff) and reported by name():
//   CUDA-GL interop     the pages and the pose buffer are mapped into CUDA: device-to-device copies only;
//   GL-OpenCL bridge    OpenCL without gl_sharing (NVIDIA): GL and OpenCL import memory CUDA exports;
//   cl_khr_gl_sharing   OpenCL on a context created against the GL context: GL objects used in place;
//   staged copy         poses via the host, each page read once straight into the mapped atlas buffer.
#include <memory>
#include <string>
#include <vector>

#include "atlas/gl/atlas_renderer.hpp"
#include "compute/buffer.hpp"

namespace depthtrack::interop {

class AtlasHandoff {
 public:
  virtual ~AtlasHandoff() = default;
  // Puts the particles' states (DT_STATE_STRIDE floats each) into the renderer's pose buffer.
  virtual void send_poses(const compute::Buffer<float>& states) = 0;
  // Copies the rendered pages into `atlas` (layout().floats() floats), page after page as they lie.
  virtual void receive_atlas(compute::Buffer<float>& atlas) = 0;
  // e.g. "CUDA-GL interop (zero-copy)", "staged copy (OpenCL platform lacks cl_khr_gl_sharing)".
  virtual std::string name() const = 0;
};

// The best hand-off between `queue` and `renderer`, whose pages must already be reserve()d (they are
// registered once). Falls back to the staged copy, saying why in name(); BackendError only when a
// path the platform advertises fails outright. `shared_context_refused` (GlAtlasDevice's): why the
// queue's context is not one made against the renderer's GL context, reported instead of the general
// reason when cl_khr_gl_sharing is listed.
std::unique_ptr<AtlasHandoff> make_atlas_handoff(compute::Queue& queue, render::AtlasRenderer& renderer,
                                                 const std::string& shared_context_refused = {});

// The paths, for make_atlas_handoff and tests. make_cuda_gl_handoff returns null, with the reason in
// `why_not`, when the queue is not CUDA or the GL context does not run on its device.
std::unique_ptr<AtlasHandoff> make_staged_handoff(compute::Queue& queue, render::AtlasRenderer& renderer,
                                                  std::string reason);
std::unique_ptr<AtlasHandoff> make_cuda_gl_handoff(compute::Queue& queue, render::AtlasRenderer& renderer,
                                                   std::string& why_not);
// OpenCL without cl_khr_gl_sharing, through memory CUDA exports (needs the NVIDIA driver's CUDA).
std::unique_ptr<AtlasHandoff> make_opencl_gl_bridge_handoff(compute::Queue& queue, render::AtlasRenderer& renderer,
                                                            std::string& why_not);
// OpenCL with cl_khr_gl_sharing, on a queue whose context was created against the renderer's GL
// context (interop/gl_sharing/gl_shared_queue.hpp); null, saying why, otherwise.
std::unique_ptr<AtlasHandoff> make_cl_gl_sharing_handoff(compute::Queue& queue, render::AtlasRenderer& renderer,
                                                         std::string& why_not);
// Poses for paths that move them through the host: download the states, upload them to GL.
void send_poses_through_host(const compute::Buffer<float>& states, render::AtlasRenderer& renderer,
                             std::vector<float>& host);

}  // namespace depthtrack::interop
