// The atlas drawn by OpenGL, all particles in one instanced call per page, and handed to the
// compute kernels by the best path the platform has (src/interop/).
#include "atlas/atlas_source.hpp"
#include "atlas/gl/atlas_renderer.hpp"
#include "atlas/gl/gl_context.hpp"
#include "core/stopwatch.hpp"
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
        renderer_(context_, mesh, camera, config.near_plane, config.observation.max_depth) {
    renderer_.reserve(config.particles);
    handoff_ = interop::make_atlas_handoff(queue, renderer_);
  }

  const render::AtlasLayout& layout() const override { return renderer_.layout(); }

  compute::EventPtr draw(const compute::Buffer<float>& states, compute::Buffer<float>& atlas,
                         StepTimings& timings) override {
    Stopwatch clock;
    handoff_->send_poses(states);
    timings.handoff_ms += clock.lap_ms();
    renderer_.draw();
    renderer_.finish();  // so that the split below is GL's time, not the hand-off's wait for it
    timings.render_ms += clock.lap_ms();
    handoff_->receive_atlas(atlas);
    timings.handoff_ms += clock.lap_ms();
    return nullptr;
  }
  std::string description() const override { return "GL (" + context_.describe() + "); hand-off: " + handoff_->name(); }

 private:
  render::GlContext context_;
  render::AtlasRenderer renderer_;
  std::unique_ptr<interop::AtlasHandoff> handoff_;
};
}  // namespace

std::unique_ptr<AtlasSource> make_gl_atlas_source(compute::Queue& queue, const Mesh& mesh, const Camera& camera,
                                                  const TrackerConfig& config) {
  return std::make_unique<GlAtlasSource>(queue, mesh, camera, config);
}

}  // namespace depthtrack
