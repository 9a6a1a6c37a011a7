#pragma once
// The particle filter on a compute device (OpenCL or CUDA through src/compute): propagate, weigh,
// normalize and estimate, refine, resample, all in kernels from cl/, as the filter's FramePlan
// (filter/frame_plan.hpp) lays them out and FrameSteps (filter/frame_steps.hpp) launches them. The pose atlas it weighs
// comes from an AtlasSource: a compute kernel on this device, the GL renderer fed from and handing back to device
// memory, or the reference rasterizer on the host. Per frame only the depth image goes up and the estimate comes back.
#include <memory>
#include <optional>
#include <vector>

#include "atlas/atlas_source.hpp"
#include "compute/program_cache.hpp"
#include "filter/filter_buffers.hpp"
#include "filter/frame_plan.hpp"
#include "filter/frame_steps.hpp"
#include "filter/frame_time_table.hpp"
#include "filter/state_rows.hpp"
#include "model/filter_backend.hpp"
#include "model/particle.hpp"
#include "model/state_window.hpp"

namespace depthtrack {

class DevicePoseScorer;
class DeviceRefiner;
struct DevicePoseScorerPrograms;

class DeviceFilter final : public FilterBackend {
 public:
  // On a device of its own.
  DeviceFilter(std::unique_ptr<compute::Queue> queue, const Mesh& mesh, const Camera& camera,
               const TrackerConfig& config);
  // On a device other filters may share: its queue, and its programs (built once for them all). With
  // config.renderer gl, `gl` is the Device's GL side (Device::gl_atlas; `device` is then gl->compute), whose
  // GL context the atlas is drawn in; without it the GL atlas makes a context of its own.
  DeviceFilter(std::shared_ptr<compute::DeviceContext> device, const Mesh& mesh, const Camera& camera,
               const TrackerConfig& config, const GlAtlasDevice* gl = nullptr);
  ~DeviceFilter() override;
  DeviceFilter(const DeviceFilter&) = delete;  // its steps keep references to its members
  DeviceFilter& operator=(const DeviceFilter&) = delete;

  void initialize(const Pose& pose, const InitialSpread& spread) override;
  void initialize_modes(std::span<const Pose> modes, const InitialSpread& spread) override;
  // Through a DevicePoseScorer made on first use (its atlas is separate from the filter's).
  std::vector<double> score_poses(std::span<const Pose> poses, const DepthImage& depth,
                                  const ObservationModel& model) override;
  // A DevicePoseScorer on this filter's queue; the scoring programs are built on the first call
  // and shared by every scorer made after it.
  std::unique_ptr<PoseScorer> make_pose_scorer(const Mesh& mesh) override;
  Estimate update(const DepthImage& depth, double dt) override;
  // Enqueues the whole frame on this filter's queue (the depth's upload blocks on it alone);
  // collect() reads the estimate back, the frame's one wait.
  void enqueue_update(const DepthImage& depth, double dt) override;
  Estimate collect() override;
  std::string description() const override;
  std::pair<int, int> occlusion_window_size() const override { return {window_.width, window_.height}; }
  // The reference's draw of the new cloud from the current weights (ReferenceFilter::set_particle_count),
  // made on the host from the device's log weights; the kinematic states are gathered on the device and
  // each child reads its particle's occlusion rows (the parents), so nothing is allocated: the buffers
  // hold the configuration's particles from the start. The plan follows the count (frame_plan_layouts).
  void set_particle_count(int count) override;

  // The kernels, layouts and work sizes this filter's frame runs (at its current count).
  const FramePlan& plan() const { return plan_; }

 private:
  friend class DeviceFilterProbe;  // what tests inspect and set (filter/device_filter_probe.hpp)
  void read_step_times(FrameEvents& events, StepTimings& timings) const;
  struct Pending;  // a frame between enqueue_update and collect: its clock and events

  std::shared_ptr<compute::DeviceContext> device_;
  // A queue of this filter's own on device_ (so several filters' work overlaps), where the backend
  // offers one; queue_ is it, or else device_'s.
  std::unique_ptr<compute::Queue> own_queue_;
  compute::Queue* queue_;
  TrackerConfig config_;
  Camera camera_;
  Eigen::Vector3d centre_;
  Mesh mesh_;  // kept for score_poses' scorer, made only when it is first called
  FrameSizes sizes_;
  FramePlan plan_;                  // the current count's (the configuration's until set_particle_count)
  std::vector<FramePlan> layouts_;  // every count's layout (frame_plan_layouts), whose kernels are built
  size_t rows_particles_ = 0;       // the particles whose occlusion rows the current rows hold
  // The state window (TrackerConfig::occlusion_window): where the occlusion rows lie (window_), and
  // where the next frame keeps them (next_window_: centred on the last estimate; an automatic window
  // sized from the object's extent).
  model::ObjectExtent extent_;
  model::StateWindow window_, next_window_;
  StateRows rows_;  // checks the memory before anything is allocated
  std::unique_ptr<AtlasSource> atlas_source_;
  FilterBuffers buffers_;
  std::unique_ptr<FrameTimeTable> frame_times_;
  std::unique_ptr<DeviceRefiner> refiner_;  // when config.refine.enabled
  std::unique_ptr<FrameSteps> steps_;
  std::unique_ptr<PoseScorer> scorer_;
  std::shared_ptr<const DevicePoseScorerPrograms> scoring_programs_;
  std::unique_ptr<Pending> pending_;
  bool keep_atlas_ = false;
  bool last_resampled_ = false;
  bool weighed_in_scratch_ = false;  // the last update left the weighed states in scratch_state
  unsigned frame_ = 0;
  double time_ = 0;
};

}  // namespace depthtrack
