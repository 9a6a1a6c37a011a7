#pragma once
// The pose refinement on the device: after weighing, the heaviest particle's pose is fitted to the
// frame's likelihood and the refined pose, its covariance and the steps tried go into the estimate
// buffer, the correction that moved the heaviest particle there into correction(), by which the
// resampling moves every particle (resample_particles). Three layouts of the same fit
// (Refinement::layout): the whole fit in one work-group and one launch (cl/refine.cl), or each
// step's rendering and sums spread over many work-groups, the sums' last group solving and deciding
// (cl/refine_spread.cl: 2 launches a step, iterations + 1 evaluations enqueued per stage of the fit, the
// ones after convergence returning at once; it needs 64-bit atomics), or the spread layout's kernels as one
// work-group's loop, one launch (refine_spread.cl's refine_one_launch; 64-bit atomics too). Its own program, built with
// a larger work-group than the filter's kernels. Reference: reference::PoseRefiner and ReferenceFilter::refine.
#include <Eigen/Core>
#include <depthtrack/camera.hpp>
#include <depthtrack/mesh.hpp>
#include <depthtrack/tracker_config.hpp>
#include <memory>
#include <string>
#include <vector>

#include "atlas/raster_inputs.hpp"
#include "compute/buffer.hpp"
#include "compute/device_info.hpp"
#include "compute/program_cache.hpp"
#include "dt_params.h"

namespace depthtrack {

// The buffers of the filter that the fit reads (the heaviest particle's index is in estimate).
struct RefineInputs {
  const compute::Buffer<float>& states;
  const compute::Buffer<float>& observed;
  // The occlusion state from before this frame's weigh, particle i's in row parents[i] (cl/weigh.cl):
  // the heaviest particle's, aged to now, is the fit's occlusion prior.
  const compute::Buffer<float>& occlusion;
  const compute::Buffer<uint16_t>& occlusion_time;  // frame indices (cl/dt_time_index.h)
  const compute::Buffer<float>& frame_times;
  const compute::Buffer<unsigned>& parents;
  dt_window window;  // the state window this frame and the rows' (model::window_params)
  double time;       // seconds since the first frame
  double dt;         // seconds since the frame before
};

// summarize.cl's inputs, for the one-launch fit that summarizes first (DeviceRefiner::summarizes_first).
struct SummaryInputs {
  const compute::Buffer<float>& log_weight;
  const compute::Buffer<float>& log_likelihood;
  compute::Buffer<float>& weights;  // the normalized weights, written
  unsigned count;
  Eigen::Vector3f centre;  // the mesh's, object frame
  float kl_threshold;      // model::float_threshold of the resampling's
};

// The layout Auto picks: Spread for meshes of kSpreadTriangles triangles or more on every device, and
// for smaller ones on devices whose queue replays its launches (DeviceInfo::replayed_launches: CUDA's graphs) and
// on GPUs over kOneLaunchGpuPixels; OneLaunch for smaller meshes elsewhere (measured on PoCL and NVIDIA's
// CUDA and OpenCL: device_refiner.cpp); OneGroup on devices without 64-bit atomic min
// (DeviceInfo::int64_atomics), where Spread or OneLaunch asked for is an InputError.
constexpr size_t kSpreadTriangles = 2048;
// On a GPU, OneLaunch's one group sums every pixel of the image in each evaluation: beyond this many
// pixels (160x120; measured at 80x60 only) a GPU spreads. A CPU runs a group's work-items in sequence
// anyway (PoCL: one-launch the fastest at 80x60, 160x120 and 320x240).
constexpr size_t kOneLaunchGpuPixels = 160 * 120;
RefineLayout resolved_refine_layout(RefineLayout layout, const compute::DeviceInfo& device, size_t triangle_count,
                                    size_t pixel_count);

// The work-items that draw each triangle of the fit's candidate, every draw_slices-th row each (a coarse
// mesh's few large triangles, a work-item each, kept the fit waiting on their pixel loops). On a GPU: with
// the spread layout enough for about kFitDrawItems items over the device; with the one-group layouts only
// the group's otherwise idle work-items (floor(group / triangles): a mesh of as many triangles as the group
// has work-items is drawn whole, as before). Every slice repeats the triangle's set-up: with 2,048 items in
// one group, about 10 a work-item for the handset's 842 triangles against 3-4, NVIDIA OpenCL's one-launch
// fit at 80x60 took 0.19 -> 0.21 ms a frame (H100). At most one per row of the image
// and kMaxDrawSlices. 1 on a CPU, whose work-items run in turn anyway.
constexpr size_t kFitDrawItems = 2048;
constexpr unsigned kMaxDrawSlices = 64;
unsigned refine_draw_slices(RefineLayout layout, size_t triangle_count, int image_height, bool gpu);

class DeviceRefiner {
 public:
  // occlusion_definition: the filter kernels' DT_OCCLUSION definition (model::occlusion_definition).
  // refine.cl / refine_spread.cl come from programs, the cache of queue's device. draw_slices: 0 for
  // refine_draw_slices' choice for this device, or that many (tests: the same fit for any).
  DeviceRefiner(compute::Queue& queue, compute::ProgramCache& programs, const Mesh& mesh, const Camera& camera,
                const TrackerConfig& config, const std::string& occlusion_definition, unsigned draw_slices = 0);

  // Enqueues the fit; estimate holds summarize's output and receives the refined pose. With summary
  // (only where summarizes_first()), summarize.cl's work is done first in the fit's own launch and
  // estimate needs no summary before. The events of every kernel it enqueued, in order (their device
  // times add up to the fit's).
  std::vector<compute::EventPtr> refine(compute::Buffer<float>& estimate, const RefineInputs& in,
                                        const SummaryInputs* summary = nullptr);
  // Whether this layout can summarize in its own launch: one-launch (one group, as summarize.cl's).
  bool summarizes_first() const { return layout_ == RefineLayout::OneLaunch; }
  // The twist that moves the heaviest particle onto the last fit's refined pose, about the mesh's
  // centre: resample_particles (cl/resample.cl) moves every particle by it.
  const compute::Buffer<float>& correction() const { return correction_; }

  RefineLayout layout() const { return layout_; }  // never Auto
  unsigned draw_slices() const { return draw_slices_; }
  double radius() const { return radius_; }  // the mesh's (model::pose_covariance's pivot)

 private:
  std::vector<compute::EventPtr> refine_spread(compute::Buffer<float>& estimate, const RefineInputs& in,
                                               const dt_refine_args& args);

  compute::Queue& queue_;
  std::vector<TrackerConfig> stages_;  // model::fit_stages: the fit's one or two stages, as the reference's
  TrackerConfig config_;               // the first stage's
  Camera camera_;
  Eigen::Vector3d centre_;
  double radius_;
  RefineLayout layout_;
  unsigned draw_slices_;
  std::shared_ptr<compute::Program> program_;
  std::unique_ptr<compute::Kernel> refine_;
  // The spread layout's kernels (cl/refine_spread.cl), its fit state, per-group partial sums and
  // the candidate's drawing (depth bits and triangle per pixel).
  std::unique_ptr<compute::Kernel> begin_, draw_, sums_;
  size_t sum_groups_ = 0;
  compute::Buffer<float> fit_state_;
  compute::Buffer<uint64_t> partials_, nearest_;  // (stamp << 32) | sum bits; (depth bits << 32) | triangle
  MeshBuffers mesh_;
  compute::Buffer<float> correction_;  // the twist the cloud follows
  // The one-group layout's one-pose scratch (state, depth bits, triangle ids).
  compute::Buffer<float> pose_;
  compute::Buffer<unsigned> tile_, ids_;
};

}  // namespace depthtrack
