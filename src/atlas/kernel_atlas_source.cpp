// The atlas rasterized on the filter's own compute device by cl/rasterize.cl: the kernel reads the
// particle states where they are and writes the atlas in place, so nothing crosses to the host.
#include <depthtrack/error.hpp>
#include <string>
#include <vector>

#include "atlas/atlas_source.hpp"
#include "atlas/raster_inputs.hpp"
#include "compute/program_cache.hpp"
#include "dt_state.h"
#include "model/kernel_params.hpp"

namespace depthtrack {

namespace {
// Work-items per particle, striding over the triangles. On the H100, 128 is the fastest for the
// handset at 80x60 (64: 10 % slower; 256 gains only at 640x480, 5-17 %); PoCL does not care.
constexpr size_t kGroupSize = 128;

class KernelAtlasSource final : public AtlasSource {
 public:
  KernelAtlasSource(compute::Queue& queue, compute::ProgramCache& programs, const Mesh& mesh, const Camera& camera,
                    const TrackerConfig& config)
      : queue_(queue),
        // Particle-major: cl/rasterize.cl writes each tile as one contiguous block.
        layout_(render::AtlasLayout::particle_major(config.particles, camera.width, camera.height)),
        camera_(model::camera_params(camera, config)),
        program_(programs.program("rasterize.cl", rasterize_definitions(kGroupSize, queue.info()))),
        kernel_(program_->kernel("rasterize")),
        mesh_(queue_, mesh) {}

  const render::AtlasLayout& layout() const override { return layout_; }

  // Enqueued on the filter's queue: its event times it (render_ms), nothing waits here.
  compute::EventPtr draw(const compute::Buffer<float>& states, compute::Buffer<float>& atlas, StepTimings&) override {
    const size_t particles = static_cast<size_t>(layout_.tiles_per_page);  // one page of them all
    if (states.size() < particles * DT_STATE_STRIDE || atlas.size() < layout_.floats())
      throw InputError("kernel atlas source: the state or atlas buffer is smaller than " + std::to_string(particles) +
                       " particles need");
    // The atlas is written as the depths' bits.
    return queue_.launch(*kernel_, compute::NdRange::linear(particles * kGroupSize, kGroupSize), states, mesh_.vertices,
                         mesh_.triangles, mesh_.planes, mesh_.triangle_count(), mesh_.vertex_count(), camera_,
                         layout_.kernel_args(), atlas, boxes_, static_cast<unsigned>(boxed_));
  }

  const MeshBuffers* device_mesh() const override { return &mesh_; }

  void draw_boxed() override {
    boxed_ = true;
    boxes_ = compute::Buffer<unsigned>(queue_, 4 * static_cast<size_t>(layout_.tiles_per_page));
  }
  const compute::Buffer<unsigned>* tile_boxes() const override { return boxed_ ? &boxes_ : nullptr; }

  std::string description() const override {
    return "compute-kernel rasterizer on " + queue_.info().name + "; hand-off: none (rendered in device memory)";
  }

 private:
  compute::Queue& queue_;
  render::AtlasLayout layout_;
  dt_camera camera_;
  std::shared_ptr<compute::Program> program_;
  std::unique_ptr<compute::Kernel> kernel_;
  MeshBuffers mesh_;
  bool boxed_ = false;
  compute::Buffer<unsigned> boxes_{queue_, 4};  // one box's worth until draw_boxed()
};
}  // namespace

std::unique_ptr<AtlasSource> make_kernel_atlas_source(compute::Queue& queue, compute::ProgramCache& programs,
                                                      const Mesh& mesh, const Camera& camera,
                                                      const TrackerConfig& config) {
  if (mesh.vertices.empty() || mesh.triangles.empty())
    throw InputError("the kernel rasterizer needs a mesh with triangles");
  return std::make_unique<KernelAtlasSource>(queue, programs, mesh, camera, config);
}

}  // namespace depthtrack
