// The atlas drawn tile by tile by the reference rasterizer on the host, then uploaded in one copy.
#include <vector>

#include "atlas/atlas_source.hpp"
#include "core/stopwatch.hpp"
#include "model/particle_packing.hpp"
#include "reference/rasterizer.hpp"

namespace depthtrack {

namespace {
class HostAtlasSource final : public AtlasSource {
 public:
  HostAtlasSource(const Mesh& mesh, const Camera& camera, const TrackerConfig& config)
      : rasterizer_(mesh, camera, config.near_plane, config.observation.max_depth),
        layout_(render::AtlasLayout::particle_major(config.particles, camera.width, camera.height)),
        pixels_(static_cast<size_t>(camera.pixel_count())) {}

  const render::AtlasLayout& layout() const override { return layout_; }

  compute::EventPtr draw(const compute::Buffer<float>& states, compute::Buffer<float>& atlas,
                         StepTimings& timings) override {
    Stopwatch clock;
    const std::vector<model::ParticleState> particles = unpack_particles(states.download());
    timings.handoff_ms += clock.lap_ms();
    host_.resize(particles.size() * pixels_);
    for (size_t i = 0; i < particles.size(); ++i)
      rasterizer_.render(particles[i].pose, std::span<float>(host_.data() + i * pixels_, pixels_));
    timings.render_ms += clock.lap_ms();
    atlas.upload(host_);
    timings.handoff_ms += clock.lap_ms();
    return nullptr;
  }
  std::string description() const override { return "reference rasterizer on the host; hand-off: upload"; }

 private:
  reference::Rasterizer rasterizer_;
  render::AtlasLayout layout_;
  size_t pixels_;
  std::vector<float> host_;
};
}  // namespace

std::unique_ptr<AtlasSource> make_host_atlas_source(compute::Queue&, const Mesh& mesh, const Camera& camera,
                                                    const TrackerConfig& config) {
  return std::make_unique<HostAtlasSource>(mesh, camera, config);
}

}  // namespace depthtrack
