#pragma once
// Where the device filter's pose atlas comes from: every particle's rendered metric depth (0 = not
// covered) in a device buffer, tile i = particle i, laid out as layout() says (cl/dt_atlas.h).
// Each source also reports how the atlas reaches the kernels.
#include <depthtrack/camera.hpp>
#include <depthtrack/mesh.hpp>
#include <depthtrack/tracker.hpp>
#include <depthtrack/tracker_config.hpp>
#include <memory>
#include <string>

#include "atlas/atlas_layout.hpp"
#include "atlas/raster_inputs.hpp"
#include "compute/buffer.hpp"
#include "compute/program_cache.hpp"

namespace depthtrack {

class AtlasSource {
 public:
  virtual ~AtlasSource() = default;
  // Fixed for the source's life: config.particles tiles, or fewer where the source draws in turns
  // (the kernel source: kernel_atlas_tiles).
  virtual const render::AtlasLayout& layout() const = 0;
  // Draws particle i of `states` (DT_STATE_STRIDE floats each, cl/dt_state.h) into tile i of
  // `atlas` (layout().floats() floats). Drawing on the compute queue enqueues and returns its event
  // without waiting (the caller adds its device time to render_ms once the frame is done); drawing
  // elsewhere adds its host time, and that of the hand-off up to the point where its work is
  // enqueued, to `timings` and returns nullptr.
  virtual compute::EventPtr draw(const compute::Buffer<float>& states, compute::Buffer<float>& atlas,
                                 StepTimings& timings) = 0;
  // Draws particles [first, first + count) of `states` into tiles 0 .. count - 1, enqueued as draw() is:
  // for a layout of fewer tiles than particles, drawn and weighed in turns. Only the kernel source
  // draws so; the others hold every particle's tile (InputError here).
  virtual compute::EventPtr draw_range(const compute::Buffer<float>& states, compute::Buffer<float>& atlas,
                                       size_t first, size_t count);
  // e.g. "GL (EGL device 0: ...); hand-off: CUDA-GL interop (zero-copy)".
  virtual std::string description() const = 0;
  // The mesh as the compute kernels draw it, where this source keeps it on the filter's device (the
  // kernel source: the filter's render_weigh draws from it too), else null.
  virtual const MeshBuffers* device_mesh() const { return nullptr; }
  // Asks the source to draw only each pose's box of its tile from now on, leaving the rest of the tile
  // as it was, and to keep the boxes (4 per particle: u0, v0, width, height) for the weigh kernel.
  // Where it can (the kernel source), tile_boxes() then holds them; elsewhere it stays null.
  virtual void draw_boxed() {}
  virtual const compute::Buffer<unsigned>* tile_boxes() const { return nullptr; }
};

// The kernel source's tiles: every particle's, or at most atlas_particles (TrackerConfig; 0: no limit) and
// at most what one buffer of max_allocation bytes holds (0: unknown), at least one.
size_t kernel_atlas_tiles(size_t particles, size_t pixels, int atlas_particles, size_t max_allocation);

struct GlAtlasDevice;  // atlas/gl_atlas_device.hpp

// The source TrackerConfig::renderer names: "kernel" (cl/rasterize.cl on the filter's device), "gl"
// (the OpenGL atlas renderer; BackendError naming every GL path tried when none works) or "cpu"
// (the reference rasterizer on the host). Every source works on `queue`, a queue of the device the cache
// builds for (a filter's own, DeviceContext::make_queue); the kernel source takes its program from the cache.
// The GL source draws in `gl`'s context (the Device's, shared; `queue` then belongs to gl->compute), or,
// without one, in a GL context of its own.
std::unique_ptr<AtlasSource> make_atlas_source(compute::Queue& queue, compute::ProgramCache& programs, const Mesh& mesh,
                                               const Camera& camera, const TrackerConfig& config,
                                               const GlAtlasDevice* gl = nullptr);
// The same on the cache's own queue.
std::unique_ptr<AtlasSource> make_atlas_source(compute::ProgramCache& programs, const Mesh& mesh, const Camera& camera,
                                               const TrackerConfig& config);

}  // namespace depthtrack
