#include "filter/frame_plan.hpp"

#include <algorithm>
#include <cstdint>

#include "atlas/atlas_source.hpp"
#include "atlas/raster_inputs.hpp"
#include "compute/resident_groups.hpp"
#include "dt_draw_list.h"
#include "dt_state.h"
#include "filter/device_refiner.hpp"
#include "filter/wide_summary.hpp"
#include "model/state_window.hpp"

namespace depthtrack {

namespace {
constexpr size_t kStaticLocalLimit = 48 * 1024;  // CUDA's for a block's static shared memory

size_t round_up(size_t n, size_t multiple) {
  return (n + multiple - 1) / multiple * multiple;
}

// The tile, and the pose box's reduction, which the group sum reuses.
size_t render_weigh_local_bytes(size_t pixels) {
  return pixels * sizeof(float) + pose_box_scratch_bytes(kFilterGroup);
}

// render_weigh's work-group memory with shared_points' projections kept: the tile and reduction, the
// points, the triangle list (cl/dt_draw_list.h) with each one's first row, and its tally.
size_t render_weigh_group_bytes(size_t tile_pixels, size_t shared_points) {
  static_assert((uint64_t{DT_DRAW_LIST} << DT_ROW_BITS) < (uint64_t{1} << 32), "a full list's tally overflows 32 bits");
  return render_weigh_local_bytes(tile_pixels) +
         (shared_points > 0 ? shared_points * 2 * sizeof(float) + (2 * DT_DRAW_LIST + 1) * sizeof(unsigned) : 0);
}
}  // namespace

double device_filter_bytes_per_particle(size_t pixels, OcclusionStorage mode, bool gl_pages, bool atlas,
                                        std::optional<size_t> state_pixels) {
  const bool occlusion = mode != OcclusionStorage::Off, times = mode == OcclusionStorage::PerPixelTime;
  const double image_floats = (atlas ? 1 : 0) + (gl_pages ? 2 : 0);
  const double state_floats = (occlusion ? 2 : 0) + (times ? 1 : 0);  // times: 2 x 16 bits
  const double kept = static_cast<double>(state_pixels.value_or(pixels));
  return 4.0 * (static_cast<double>(pixels) * image_floats + kept * state_floats +
                (2 + (gl_pages ? 1 : 0)) * DT_STATE_STRIDE + 6);
}

bool renders_inside_weigh(Renderer renderer, size_t pixels, size_t local_memory) {
  return renderer == Renderer::Kernel && render_weigh_local_bytes(pixels) <= std::min(local_memory, kStaticLocalLimit);
}

size_t kernel_renderer_atlas_tiles(const TrackerConfig& config, size_t pixels, size_t local_memory,
                                   size_t max_allocation) {
  if (renders_inside_weigh(Renderer::Kernel, pixels, local_memory)) return 0;
  return kernel_atlas_tiles(static_cast<size_t>(config.particles), pixels, config.atlas_particles, max_allocation);
}

bool propagates_inside_weigh(Renderer renderer, size_t pixels, size_t local_memory, size_t particles) {
  return particles <= kFusedLaunchParticles && renders_inside_weigh(renderer, pixels, local_memory);
}

size_t render_weigh_shared_points(size_t tile_pixels, size_t vertex_count, size_t local_memory) {
  const size_t needed = render_weigh_group_bytes(tile_pixels, vertex_count);
  return vertex_count > 0 && needed <= std::min(local_memory, kStaticLocalLimit) ? vertex_count : 0;
}

size_t render_weigh_resident_groups(size_t tile_pixels, size_t shared_points, const compute::DeviceInfo& device) {
  return compute::resident_groups(render_weigh_group_bytes(tile_pixels, shared_points), kFilterGroup, device);
}

RenderWeighLayout render_weigh_layout(int width, int height, size_t vertex_count, const compute::DeviceInfo& device) {
  auto layout = [&](size_t tile) {
    RenderWeighLayout l;
    l.tile_pixels = tile;
    l.shared_points = render_weigh_shared_points(tile, vertex_count, device.local_memory);
    l.resident_groups = render_weigh_resident_groups(tile, l.shared_points, device);
    return l;
  };
  const RenderWeighLayout whole = layout(static_cast<size_t>(width) * static_cast<size_t>(height)),
                          half = layout(static_cast<size_t>(width) * static_cast<size_t>((height + 1) / 2));
  return half.resident_groups >= whole.resident_groups + 2 || half.shared_points > whole.shared_points ? half : whole;
}

size_t summary_group_size(const compute::DeviceInfo& device) {
  if (!device.is_gpu) return kFilterGroup;
  size_t size = kFilterGroup;
  while (size * 2 <= std::min<size_t>(DT_SUMMARY_GPU_GROUP, device.max_work_group_size)) size *= 2;
  return size;
}

compute::NdRange FramePlan::per_particle() const {
  return compute::NdRange::linear(round_up(particles, kLinearGroup), kLinearGroup);
}

compute::NdRange FramePlan::group_per_particle(size_t groups) const {
  return compute::NdRange::linear(groups * kFilterGroup, kFilterGroup);
}

compute::NdRange FramePlan::scanning() const {
  return compute::NdRange::linear(round_up(particles, kFilterGroup), kFilterGroup);
}

FrameSizes frame_sizes(const Mesh& mesh, const Camera& camera, const TrackerConfig& config) {
  FrameSizes sizes;
  sizes.width = camera.width;
  sizes.height = camera.height;
  sizes.triangles = mesh.triangles.size();
  // The kernel renderer's source keeps the mesh as given on the device (KernelAtlasSource::device_mesh).
  if (config.renderer == Renderer::Kernel) sizes.device_mesh_vertices = mesh.vertices.size();
  sizes.whole_image_state =
      !config.occlusion_window.is_automatic() &&
      model::state_window_size(config, camera).pixels() == static_cast<size_t>(camera.pixel_count());
  return sizes;
}

FramePlan make_frame_plan(const TrackerConfig& config, const compute::DeviceInfo& device, const FrameSizes& sizes,
                          std::optional<size_t> particles) {
  FramePlan plan;
  plan.particles = particles.value_or(static_cast<size_t>(config.particles));
  plan.pixels = static_cast<size_t>(sizes.width) * static_cast<size_t>(sizes.height);
  plan.whole_image_state = sizes.whole_image_state;
  if (sizes.device_mesh_vertices && renders_inside_weigh(config.renderer, plan.pixels, device.local_memory)) {
    plan.weigh = WeighStep::RenderWeigh;
    plan.propagate_in_weigh =
        propagates_inside_weigh(config.renderer, plan.pixels, device.local_memory, plan.particles);
    plan.render_weigh = render_weigh_layout(sizes.width, sizes.height, *sizes.device_mesh_vertices, device);
  }
  if (config.renderer == Renderer::Kernel)
    plan.atlas_tiles = kernel_renderer_atlas_tiles(config, plan.pixels, device.local_memory, device.max_allocation);
  if (config.refine.enabled)
    plan.refine = resolved_refine_layout(config.refine.layout, device, sizes.triangles, plan.pixels);
  // The summary and prefix sum: one group for a few thousand particles, many for large clouds; a small
  // cloud's resampling groups scan the weights themselves. The one-launch fit summarizes in its own
  // group first (one launch for both); a wide summary stays apart.
  if (plan.particles >= kWideSummaryParticles)
    plan.summary = SummaryStep::Wide;
  else if (plan.refine == RefineLayout::OneLaunch)
    plan.summary = SummaryStep::InsideFit;
  if (plan.builds_summarize()) plan.summary_group = summary_group_size(device);
  if (plan.particles <= kFusedLaunchParticles)
    plan.resample = ResampleStep::Scanning;
  else
    plan.resample = plan.summary == SummaryStep::Wide ? ResampleStep::WidePrefixSum : ResampleStep::PrefixSum;
  return plan;
}

std::vector<FramePlan> frame_plan_layouts(const TrackerConfig& config, const compute::DeviceInfo& device,
                                          const FrameSizes& sizes) {
  const size_t most = static_cast<size_t>(config.particles);
  std::vector<FramePlan> plans;
  for (const size_t count : {size_t{1}, kFusedLaunchParticles, kFusedLaunchParticles + 1, kWideSummaryParticles - 1,
                             kWideSummaryParticles, most})
    if (count <= most && (plans.empty() || plans.back().particles < count)) {
      FramePlan plan = make_frame_plan(config, device, sizes, count);
      const bool same = !plans.empty() && plans.back().propagate_in_weigh == plan.propagate_in_weigh &&
                        plans.back().summary == plan.summary && plans.back().resample == plan.resample;
      if (same && count != most) continue;
      if (same) plans.pop_back();  // the most's plan stands for its layout
      plans.push_back(plan);
    }
  return plans;
}

std::optional<kernels::SummaryKernel> FramePlan::summary_kernel() const {
  switch (summary) {
    case SummaryStep::OneGroup:
      return kernels::SummaryKernelOf<kernels::SummarizeArgs>{};
    case SummaryStep::Wide:
    case SummaryStep::InsideFit:
      break;
  }
  return std::nullopt;
}

}  // namespace depthtrack
