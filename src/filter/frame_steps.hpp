#pragma once
// The device filter's kernels, built as its FramePlan says (only those the frame launches: a CPU device
// compiles each for a while), and one method per step of the frame that launches them with named
// arguments (filter/kernels/). DeviceFilter::enqueue_update runs the steps in order.
#include <Eigen/Core>
#include <memory>
#include <span>
#include <vector>

#include "atlas/atlas_source.hpp"
#include "compute/program_cache.hpp"
#include "dt_params.h"
#include "filter/filter_buffers.hpp"
#include "filter/frame_plan.hpp"
#include "filter/frame_time_table.hpp"
#include "filter/state_rows.hpp"

namespace depthtrack {

class WideSummary;

// What a frame's launches take that changes from frame to frame.
struct FrameInputs {
  float now = 0, dt = 0;   // seconds since the first frame, since the one before
  unsigned now_index = 0;  // the frame's time index (cl/dt_time_index.h)
  unsigned frame = 0;      // counts frames since the start (the random streams')
  bool moves = false;      // dt > 0: the particles take the motion step
  dt_motion motion{};
  dt_window window{};  // the state window now and the rows' (model::window_params)
};

// A frame's device work in progress: the events of its steps (null where untimed).
struct FrameEvents {
  StepTimings timings;  // the atlas source's host part
  compute::EventPtr propagated;
  std::vector<compute::EventPtr> rendered, weighed;  // one each per turn of the atlas' tiles
  std::vector<compute::EventPtr> summarized, refined, resampling;
};

class FrameSteps {
 public:
  // The plan, buffers, rows, times and atlas source are the filter's and outlive the steps. plan: the current
  // count's, which the steps read at each launch (the filter replaces it when its count changes); layouts:
  // every layout it may take (frame_plan_layouts), whose kernels are built now.
  FrameSteps(compute::Queue& queue, compute::ProgramCache& programs, const FramePlan& plan,
             std::span<const FramePlan> layouts, const TrackerConfig& config, const Camera& camera, AtlasSource& atlas,
             FilterBuffers& buffers, StateRows& rows, FrameTimeTable& times);
  ~FrameSteps();

  // The start (cl/initialize.cl): particle i drawn around mode i % modes, weights equal, parents the
  // identity, the occlusion rows at their initial values; waits for it.
  void initialize(std::span<const float> modes, const dt_initial& spread, size_t state_pixels);
  void identity_parents();

  // The frame, in order.
  void propagate(const FrameInputs& in, FrameEvents& events);
  // Before any of this frame's is written; rows: those the last frame wrote (its count).
  void retire_time_indices(size_t rows, size_t state_pixels, unsigned now_index);
  void weigh(const FrameInputs& in, bool keep_atlas, FrameEvents& events);
  // centre: the mesh's; karcher_steps: the rotation mean's iterations (none where the fit replaces it).
  void summarize(const Eigen::Vector3f& centre, float kl_threshold, unsigned karcher_steps, FrameEvents& events);
  // Gathers the children into the scratch state and swaps it in (moved by correction where shift).
  void resample(unsigned frame, const Eigen::Vector3f& centre, const compute::Buffer<float>& correction, bool shift,
                FrameEvents& events);

  // Between frames, a new count (DeviceFilter::set_particle_count): count children, child j the copy of
  // particle choice[j] (cl/resample.cl's gather_states), their log weights 0.
  void gather(const compute::Buffer<unsigned>& choice, size_t count);

 private:
  struct Kernels;
  compute::Queue& queue_;
  const FramePlan& plan_;
  const TrackerConfig& config_;
  Camera camera_;
  AtlasSource& atlas_;
  FilterBuffers& b_;
  StateRows& rows_;
  FrameTimeTable& times_;
  std::unique_ptr<Kernels> k_;
  std::unique_ptr<WideSummary> wide_;  // SummaryStep::Wide
};

}  // namespace depthtrack
