// The atlas drawn by OpenGL, all particles in one instanced call per page, and handed to the
// compute kernels by the best path the platform has (src/interop/). GL's draw is timed by a
// GL_TIME_ELAPSED query read after the frame's wait, or, where GL lacks timer queries, by the host
// clock around a glFinish.
#include "atlas/atlas_source.hpp"
#include "atlas/gl/atlas_renderer.hpp"
#include "atlas/gl/gl_context.hpp"
#include "atlas/gl/gl_draw_timer.hpp"
#include "core/stopwatch.hpp"
#include "dt_state.h"
#include "interop/atlas_handoff.hpp"

namespace depthtrack {

namespace {
// The GL context for a compute device: on the EGL device that is the same GPU where EGL can tell; only the
// configuration's GL path, if it names one.
render::GlContextOptions context_options(const compute::DeviceInfo& device, const TrackerConfig& config) {
  render::GlContextOptions options;
  options.device_uuid = device.uuid;
  options.path = render::GlContext::path_from_name(config.gl_path);
  return options;
}

class GlAtlasSource final : public AtlasSource {
 public:
  GlAtlasSource(compute::Queue& queue, const Mesh& mesh, const Camera& camera, const TrackerConfig& config)
      : context_(context_options(queue.info(), config)),
        renderer_(context_, mesh, camera, config.near_plane, config.observation.max_depth),
        timer_(context_) {
    renderer_.reserve(config.particles);
    // One untimed draw (every pose behind the camera: nothing to rasterize) before the timer's first
    // query, which llvmpipe misreads on a context that has executed no command yet.
    std::vector<float> behind(static_cast<size_t>(config.particles) * DT_STATE_STRIDE, 0.0f);
    for (size_t i = 0; i < behind.size(); i += DT_STATE_STRIDE) {
      behind[i + DT_TX + 2] = -10.0f;
      behind[i + DT_QW] = 1.0f;
    }
    renderer_.upload_states(behind);
    renderer_.draw();
    renderer_.finish();
    handoff_ = interop::make_atlas_handoff(queue, renderer_);
  }

  const render::AtlasLayout& layout() const override { return renderer_.layout(); }

  compute::EventPtr draw(const compute::Buffer<float>& states, compute::Buffer<float>& atlas,
                         StepTimings& timings) override {
    Stopwatch clock;
    handoff_->send_poses(states);
    timings.handoff_ms += clock.lap_ms();
    compute::EventPtr drawn;
    if (timer_.available()) {
      // No glFinish: every hand-off waits for GL before the compute side reads (glReadPixels, a
      // glFinish before the acquire, or CUDA's map), so the wait for the draw lands in handoff_ms.
      timer_.begin();
      renderer_.draw();
      drawn = timer_.end();
    } else {
      renderer_.draw();
      renderer_.finish();  // so that the split below is GL's time, not the hand-off's wait for it
      timings.render_ms += clock.lap_ms();
    }
    clock.lap_ms();
    handoff_->receive_atlas(atlas);
    timings.handoff_ms += clock.lap_ms();
    return drawn;
  }
  std::string description() const override {
    return "GL (" + context_.describe() + "); hand-off: " + handoff_->name() +
           (timer_.available() ? "; draw timed by GL timer queries"
                               : "; draw timed by the host clock (" + timer_.why_unavailable() + ")");
  }

 private:
  render::GlContext context_;
  render::AtlasRenderer renderer_;
  render::GlDrawTimer timer_;
  std::unique_ptr<interop::AtlasHandoff> handoff_;
};
}  // namespace

std::unique_ptr<AtlasSource> make_gl_atlas_source(compute::Queue& queue, const Mesh& mesh, const Camera& camera,
                                                  const TrackerConfig& config) {
  return std::make_unique<GlAtlasSource>(queue, mesh, camera, config);
}

}  // namespace depthtrack
