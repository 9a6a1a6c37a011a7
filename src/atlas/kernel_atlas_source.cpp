// The atlas rasterized on the filter's own compute device by cl/rasterize.cl: the kernel reads the
// particle states where they are and writes the atlas in place, so nothing crosses to the host.
#include <depthtrack/error.hpp>
#include <string>
#include <vector>

#include "atlas/atlas_source.hpp"
#include "atlas/raster_inputs.hpp"
#include "compute/kernel_sources.hpp"
#include "core/stopwatch.hpp"
#include "dt_state.h"

namespace depthtrack {

namespace {
// Work-items per particle, striding over the triangles. On the H100, 128 is the fastest for the
// handset at 80x60 (64: 10 % slower; 256 gains only at 640x480, 5-17 %); PoCL does not care.
constexpr size_t kGroupSize = 128;

class KernelAtlasSource final : public AtlasSource {
 public:
  KernelAtlasSource(compute::Queue& queue, const Mesh& mesh, const Camera& camera, const TrackerConfig& config)
      : queue_(queue),
        // Particle-major: cl/rasterize.cl writes each tile as one contiguous block.
        layout_(render::AtlasLayout::particle_major(config.particles, camera.width, camera.height)),
        camera_(raster_camera_args(camera, config)),
        program_(queue.build("rasterize.cl", compute::kernel_source("rasterize.cl"),
                             {"DT_GROUP_SIZE=" + std::to_string(kGroupSize)})),
        kernel_(program_->kernel("rasterize")),
        mesh_(queue, mesh) {}

  const render::AtlasLayout& layout() const override { return layout_; }

  void draw(const compute::Buffer<float>& states, compute::Buffer<float>& atlas, StepTimings& timings) override {
    const size_t particles = static_cast<size_t>(layout_.tiles_per_page);  // one page of them all
    if (states.size() < particles * DT_STATE_STRIDE || atlas.size() < layout_.floats())
      throw InputError("kernel atlas source: the state or atlas buffer is smaller than " + std::to_string(particles) +
                       " particles need");
    Stopwatch clock;
    compute::set_arg(*kernel_, 0, states);
    compute::set_arg(*kernel_, 1, mesh_.vertices);
    compute::set_arg(*kernel_, 2, mesh_.triangles);
    compute::set_arg(*kernel_, 3, mesh_.planes);
    kernel_->set_arg(4, mesh_.triangle_count());
    kernel_->set_arg(5, camera_);
    kernel_->set_arg(6, layout_.kernel_args());
    compute::set_arg(*kernel_, 7, atlas);  // written as the depths' bits
    queue_.launch(*kernel_, compute::NdRange::linear(particles * kGroupSize, kGroupSize));
    queue_.finish();  // so that render_ms is the drawing's time, as for the other sources
    timings.render_ms += clock.lap_ms();
  }

  std::string description() const override {
    return "compute-kernel rasterizer on " + queue_.info().name + "; hand-off: none (rendered in device memory)";
  }

 private:
  compute::Queue& queue_;
  render::AtlasLayout layout_;
  RasterCameraArgs camera_;
  std::unique_ptr<compute::Program> program_;
  std::unique_ptr<compute::Kernel> kernel_;
  MeshBuffers mesh_;
};
}  // namespace

std::unique_ptr<AtlasSource> make_kernel_atlas_source(compute::Queue& queue, const Mesh& mesh, const Camera& camera,
                                                      const TrackerConfig& config) {
  if (mesh.vertices.empty() || mesh.triangles.empty())
    throw InputError("the kernel rasterizer needs a mesh with triangles");
  return std::make_unique<KernelAtlasSource>(queue, mesh, camera, config);
}

}  // namespace depthtrack
