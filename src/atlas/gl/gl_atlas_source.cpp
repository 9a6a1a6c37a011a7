// The atlas drawn by OpenGL, all particles in one instanced call per page, and handed to the
// compute kernels by the best path the platform has (src/interop/). GL's draw is timed by a
// GL_TIME_ELAPSED query read after the frame's wait, or, where GL lacks timer queries, by the host
// clock around a glFinish.
#include "atlas/atlas_source.hpp"
#include "atlas/gl/atlas_renderer.hpp"
#include "atlas/gl/gl_context.hpp"
#include "atlas/gl/gl_draw_timer.hpp"
#include "atlas/gl_atlas_device.hpp"
#include "core/stopwatch.hpp"
#include "dt_state.h"
#include "interop/atlas_handoff.hpp"

namespace depthtrack {

namespace {
// The Device's GL context where the filter got one, else one of this source's own.
std::shared_ptr<render::GlContext> context_for(const compute::Queue& queue, const TrackerConfig& config,
                                               const GlAtlasDevice* gl) {
  if (gl && gl->gl) return gl->gl;
  return std::make_shared<render::GlContext>(render::GlContextOptions::for_device(queue.info().uuid, config.gl_path));
}

class GlAtlasSource final : public AtlasSource {
 public:
  // Its own FBOs, textures and buffers (the renderer's) in a context other sources may share.
  GlAtlasSource(compute::Queue& queue, const Mesh& mesh, const Camera& camera, const TrackerConfig& config,
                const GlAtlasDevice* gl)
      : context_(context_for(queue, config, gl)),
        renderer_(*context_, mesh, camera, config.near_plane, config.observation.max_depth),
        timer_(*context_) {
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
    handoff_ = interop::make_atlas_handoff(queue, renderer_, gl ? gl->shared_context_refused : std::string());
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
    return "GL (" + context_->describe() + "); hand-off: " + handoff_->name() +
           (timer_.available() ? "; draw timed by GL timer queries"
                               : "; draw timed by the host clock (" + timer_.why_unavailable() + ")");
  }

 private:
  std::shared_ptr<render::GlContext> context_;  // first: it outlives the renderer's objects in it
  render::AtlasRenderer renderer_;
  render::GlDrawTimer timer_;
  std::unique_ptr<interop::AtlasHandoff> handoff_;
};
}  // namespace

std::unique_ptr<AtlasSource> make_gl_atlas_source(compute::Queue& queue, const Mesh& mesh, const Camera& camera,
                                                  const TrackerConfig& config, const GlAtlasDevice* gl) {
  return std::make_unique<GlAtlasSource>(queue, mesh, camera, config, gl);
}

}  // namespace depthtrack
