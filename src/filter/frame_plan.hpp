#pragma once
// The device filter's frame as a plan: which kernels a frame launches, in which layout, over which work
// sizes, and which buffers they need. Computed once from the configuration, what the device reports
// (compute::DeviceInfo) and the sizes; DeviceFilter executes it, and the memory check, the bench's
// sizing and `depthtrack bench` read the same plan. The rules each choice follows are the free
// functions below, each with the measurements behind it.
#include <cstddef>
#include <depthtrack/camera.hpp>
#include <depthtrack/mesh.hpp>
#include <optional>
#include <vector>

#include "compute/device_info.hpp"
#include "compute/queue.hpp"
#include "dt_launch.h"
#include "filter/kernels/summary_args.hpp"
#include "model/filter_backend.hpp"

namespace depthtrack {

// Work-items per group of the filter's per-particle kernels, and of its kernels that take a work-item a
// particle (cl/dt_launch.h, which the kernels read too).
constexpr size_t kFilterGroup = DT_FILTER_GROUP;
constexpr size_t kLinearGroup = DT_LINEAR_GROUP;

// Device memory one particle's buffers take (the atlas unless it is drawn inside weigh, occlusion
// probabilities and 16-bit time indices twice for the state window's state_pixels (weigh reads one and
// writes the other; none given: the image's pixels), the state twice, weights; with GL pages, GL's colour and
// depth pages and its pose buffer): what the memory check refuses by and `depthtrack bench` reports.
double device_filter_bytes_per_particle(size_t pixels, OcclusionStorage mode, bool gl_pages, bool atlas = true,
                                        std::optional<size_t> state_pixels = std::nullopt);

// Whether the filter draws each particle's tile inside weigh (cl/render_weigh.cl), the tile in
// work-group memory: with the kernel renderer, where pixels' depths fit in the device's local memory
// per group, within the 48 KiB a CUDA block may declare statically (80x60 does; 160x120 does not).
bool renders_inside_weigh(Renderer renderer, size_t pixels, size_t local_memory);

// Tiles of the separate atlas the kernel renderer draws and weighs in turns: none where it draws inside
// weigh, else kernel_atlas_tiles (config.atlas_particles, one buffer of max_allocation bytes).
size_t kernel_renderer_atlas_tiles(const TrackerConfig& config, size_t pixels, size_t local_memory,
                                   size_t max_allocation);

// Up to this many particles a frame is bound by its launches (each costs the host 5-18 us on NVIDIA's
// OpenCL) more than by its kernels, so launches are folded together: render_weigh moves its particle
// itself (no propagate launch; its program is compiled with DT_PROPAGATE_INSIDE) and every resampling
// group scans the weights itself (resample_scanning, not prefix_sum + resample_particles; the groups
// repeat the scan, count^2 / 128 adds in all, which a GPU runs side by side). Larger clouds keep the
// separate kernels, and render_weigh its registers (the moving block costs it spills in NVRTC's
// allocation).
constexpr size_t kFusedLaunchParticles = 4096;

// Whether render_weigh moves the particles (propagate.cl's step, cl/dt_propagate.h) for this cloud.
bool propagates_inside_weigh(Renderer renderer, size_t pixels, size_t local_memory, size_t particles);

// render_weigh's work-group memory: the pixels its tile holds (DT_TILE_PIXELS), the vertices whose
// projections it keeps (DT_SHARED_POINTS) and the groups a unit should hold (DT_RESIDENT_GROUPS).
struct RenderWeighLayout {
  size_t tile_pixels = 0, shared_points = 0, resident_groups = 0;
};

// The whole image's tile, or half its rows (rounded up) where that lets a unit hold at least two more
// groups or lets the mesh's projected points fit beside it: a pose's box is a small part of the image at
// the resolutions render_weigh runs at (ycbv-0000's objects at 80x60: 600-700 of 4,800 pixels), and the
// simplified mug's 1,600 points beside the whole image's tile let 5 groups onto an H100's unit, 7 with half.
// One group more was not worth it: the handset's frame at 1,000,000 particles took 20.4 ms on the H100 with
// the half tile (8 groups) against 18.2 with the whole (7). A taller box is then drawn
// and weighed in bands of rows (cl/render_weigh.cl); where the smaller tile gains less (the registers
// decide, or the device does not say what a unit holds) the tile stays whole: one band.
RenderWeighLayout render_weigh_layout(int width, int height, size_t vertex_count, const compute::DeviceInfo& device);

// How many vertices' projections render_weigh keeps in work-group memory beside its tile of tile_pixels
// (its DT_SHARED_POINTS): the mesh's vertex_count where they and the triangle list fit in the device's
// local memory (within CUDA's 48 KiB of static memory), else 0 (each triangle then projects its corners).
size_t render_weigh_shared_points(size_t tile_pixels, size_t vertex_count, size_t local_memory);

// How many render_weigh groups each compute unit should hold at once (its DT_RESIDENT_GROUPS), for its
// tile of tile_pixels and shared_points: compute::resident_groups of its work-group memory.
size_t render_weigh_resident_groups(size_t tile_pixels, size_t shared_points, const compute::DeviceInfo& device);

// The one-group summary's work-items (summarize.cl). Its passes over the particles are chains of loads,
// one per particle a work-item takes; on a GPU a bigger group makes each chain shorter (up to
// DT_SUMMARY_GPU_GROUP). A CPU runs a group's work-items in turn, so the filter's size stays there.
size_t summary_group_size(const compute::DeviceInfo& device);

// How a frame weighs: render_weigh draws each tile in work-group memory and weighs it in one launch, or
// the atlas source draws the atlas (in turns of atlas_tiles where it holds fewer) and weigh reads it.
enum class WeighStep { RenderWeigh, DrawThenWeigh };
// Where the frame's summary (normalized weights, estimate, resampling decision) is made: summarize.cl in
// one group, summarize_wide.cl over many (kWideSummaryParticles and more), or inside the one-launch fit.
enum class SummaryStep { OneGroup, Wide, InsideFit };
// How the resampling finds each child's parent: every group scans the weights (resample_scanning), or a
// prefix sum (one group, or over many with the wide summary) and then resample_particles.
enum class ResampleStep { Scanning, PrefixSum, WidePrefixSum };

// What the plan is computed from besides the configuration and the device.
struct FrameSizes {
  int width = 0, height = 0;  // the working camera's image
  size_t triangles = 0;       // the mesh's, for the fit's layout
  // The vertices of the mesh the atlas source draws on this device (AtlasSource::device_mesh), where it
  // keeps one (the kernel renderer): none, and the frame cannot draw inside weigh.
  std::optional<size_t> device_mesh_vertices;
  // A fixed state window of the whole image: weigh then indexes the state by pixel (cl/dt_window.h).
  bool whole_image_state = false;
};

// The sizes of config's filter for this mesh, seen by this camera (the working one).
FrameSizes frame_sizes(const Mesh& mesh, const Camera& camera, const TrackerConfig& config);

struct FramePlan {
  size_t particles = 0, pixels = 0;
  bool whole_image_state = false;  // the programs' DT_WHOLE_IMAGE_STATE

  WeighStep weigh = WeighStep::DrawThenWeigh;
  RenderWeighLayout render_weigh;   // WeighStep::RenderWeigh's program
  bool propagate_in_weigh = false;  // render_weigh moves the particles: no propagate launch
  size_t atlas_tiles = 0;           // the kernel renderer's separate atlas (0: drawn inside weigh, or another renderer)

  SummaryStep summary = SummaryStep::OneGroup;
  size_t summary_group = 0;  // the one-launch summary's work-items (summary_kernel)
  ResampleStep resample = ResampleStep::Scanning;
  std::optional<RefineLayout> refine;  // the fit's layout, never Auto (none: the refinement is off)

  // The work sizes: a work-item per particle (in groups of kLinearGroup), a group per particle.
  compute::NdRange per_particle() const;
  compute::NdRange group_per_particle(size_t groups) const;
  compute::NdRange one_group(size_t items) const { return compute::NdRange::linear(items, items); }
  // resample_scanning's: a work-item per particle, in the filter's groups.
  compute::NdRange scanning() const;

  // The buffers the plan needs beside those every frame has.
  bool needs_cumulative() const { return resample != ResampleStep::Scanning; }  // float-float prefix sums
  bool needs_atlas() const { return weigh == WeighStep::DrawThenWeigh; }        // else one placeholder float
  // The programs a frame does not build because their work is folded into another kernel.
  bool builds_propagate() const { return !propagate_in_weigh; }
  bool builds_summarize() const { return summary_kernel().has_value(); }
  // The kernel of a one-launch summary (cl/summarize.cl), which FrameSteps builds and launches; none for
  // the wide summary (WideSummary) and the one made inside the fit.
  std::optional<kernels::SummaryKernel> summary_kernel() const;
};

// The plan for config's filter on this device and these sizes, running `particles` (1 to
// config.particles; none given: config.particles). What is allocated (the atlas' tiles) follows
// config.particles whatever the count.
FramePlan make_frame_plan(const TrackerConfig& config, const compute::DeviceInfo& device, const FrameSizes& sizes,
                          std::optional<size_t> particles = std::nullopt);

// The plans of the counts 1 to config.particles at which make_frame_plan's count-dependent choices
// (propagate inside weigh and the scanning resampling up to kFusedLaunchParticles, the wide summary from
// kWideSummaryParticles) change, one per layout the filter may run: the kernels a filter whose count
// changes (FilterBackend::set_particle_count) builds at the start. The first is 1's layout, the last
// config.particles' plan.
std::vector<FramePlan> frame_plan_layouts(const TrackerConfig& config, const compute::DeviceInfo& device,
                                          const FrameSizes& sizes);

}  // namespace depthtrack
