// The atlas rasterized on the filter's own compute device by cl/rasterize.cl: the kernel reads the
// particle states where they are and writes the atlas in place, so nothing crosses to the host.
#include <algorithm>
#include <depthtrack/error.hpp>
#include <string>
#include <vector>

#include "atlas/atlas_source.hpp"
#include "atlas/raster_inputs.hpp"
#include "atlas/rasterize_args.hpp"
#include "compute/program_cache.hpp"
#include "dt_launch.h"
#include "dt_state.h"
#include "model/kernel_params.hpp"

namespace depthtrack {

namespace {
// Work-items per particle, striding over the triangles. On the H100, 128 is the fastest for the
// handset at 80x60 (64: 10 % slower; 256 gains only at 640x480, 5-17 %); PoCL does not care. The
// filter's group (cl/dt_launch.h), as render_weigh draws with.
constexpr size_t kGroupSize = DT_FILTER_GROUP;

class KernelAtlasSource final : public AtlasSource {
 public:
  KernelAtlasSource(compute::Queue& queue, compute::ProgramCache& programs, const Mesh& mesh, const Camera& camera,
                    const TrackerConfig& config)
      : queue_(queue),
        particles_(static_cast<size_t>(config.particles)),
        // Particle-major: cl/rasterize.cl writes each tile as one contiguous block.
        layout_(render::AtlasLayout::particle_major(
            static_cast<int>(kernel_atlas_tiles(particles_, static_cast<size_t>(camera.pixel_count()),
                                                config.atlas_particles, queue.info().max_allocation)),
            camera.width, camera.height)),
        mesh_(queue_, mesh),
        camera_(model::camera_params(camera, config, mesh_.cull_back_faces)),
        program_(programs.program("rasterize.cl", rasterize_definitions(kGroupSize, queue.info()))),
        kernel_(program_->kernel("rasterize")) {}

  const render::AtlasLayout& layout() const override { return layout_; }

  // Enqueued on the filter's queue: its event times it (render_ms), nothing waits here.
  compute::EventPtr draw(const compute::Buffer<float>& states, compute::Buffer<float>& atlas, StepTimings&) override {
    if (layout_.tiles() < particles_)
      throw InputError("kernel atlas source: " + std::to_string(particles_) + " particles in an atlas of " +
                       std::to_string(layout_.tiles()) + " tiles are drawn in turns (draw_range)");
    return draw_range(states, atlas, 0, particles_);
  }

  compute::EventPtr draw_range(const compute::Buffer<float>& states, compute::Buffer<float>& atlas, size_t first,
                               size_t count) override {
    if (count == 0 || count > layout_.tiles() || first + count > particles_ ||
        states.size() < particles_ * DT_STATE_STRIDE || atlas.size() < layout_.floats())
      throw InputError("kernel atlas source: particles " + std::to_string(first) + " to " +
                       std::to_string(first + count) + " do not fit its " + std::to_string(particles_) +
                       " particles, its atlas of " + std::to_string(layout_.tiles()) +
                       " tiles, or the state or atlas buffer given");
    return kernels::launch(
        {.queue = queue_, .kernel = *kernel_, .range = compute::NdRange::linear(count * kGroupSize, kGroupSize)},
        kernels::rasterize_args(mesh_, camera_, layout_.kernel_args(), states, atlas, boxes_,
                                static_cast<unsigned>(boxed_), static_cast<unsigned>(first)));
  }

  const MeshBuffers* device_mesh() const override { return &mesh_; }

  void draw_boxed() override {
    boxed_ = true;
    boxes_ = compute::Buffer<unsigned>(queue_, 4 * particles_);  // by particle, whichever tile it is drawn in
  }
  const compute::Buffer<unsigned>* tile_boxes() const override { return boxed_ ? &boxes_ : nullptr; }

  std::string description() const override {
    return "compute-kernel rasterizer on " + queue_.info().name + "; hand-off: none (rendered in device memory)";
  }

 private:
  compute::Queue& queue_;
  size_t particles_;
  render::AtlasLayout layout_;
  MeshBuffers mesh_;
  dt_camera camera_;
  std::shared_ptr<compute::Program> program_;
  std::unique_ptr<compute::Kernel> kernel_;
  bool boxed_ = false;
  compute::Buffer<unsigned> boxes_{queue_, 4};  // one box's worth until draw_boxed()
};
}  // namespace

size_t kernel_atlas_tiles(size_t particles, size_t pixels, int atlas_particles, size_t max_allocation) {
  size_t tiles = particles;
  if (atlas_particles > 0) tiles = std::min(tiles, static_cast<size_t>(atlas_particles));
  const size_t tile_bytes = pixels * sizeof(float);
  if (max_allocation > 0 && tile_bytes > 0) tiles = std::min(tiles, max_allocation / tile_bytes);
  return std::max<size_t>(tiles, 1);
}

std::unique_ptr<AtlasSource> make_kernel_atlas_source(compute::Queue& queue, compute::ProgramCache& programs,
                                                      const Mesh& mesh, const Camera& camera,
                                                      const TrackerConfig& config) {
  if (mesh.vertices.empty() || mesh.triangles.empty())
    throw InputError("the kernel rasterizer needs a mesh with triangles");
  return std::make_unique<KernelAtlasSource>(queue, programs, mesh, camera, config);
}

}  // namespace depthtrack
