#pragma once
// The particle filter on a compute device (OpenCL or CUDA through src/compute): propagate, weigh,
// normalize and estimate, resample, all in kernels from cl/. The pose atlas it weighs comes from
// an AtlasSource: a compute kernel on this device, the GL renderer fed from and handing back to
// device memory, or the reference rasterizer on the host. Per frame only the depth image goes up
// and the estimate comes back.
#include <memory>
#include <vector>

#include "atlas/atlas_source.hpp"
#include "atlas/raster_inputs.hpp"
#include "compute/buffer.hpp"
#include "filter/filter_backend.hpp"
#include "reference/particle.hpp"

namespace depthtrack {

class DevicePoseScorer;

class DeviceFilter final : public FilterBackend {
 public:
  DeviceFilter(std::unique_ptr<compute::Queue> queue, const Mesh& mesh, const Camera& camera,
               const TrackerConfig& config);
  ~DeviceFilter() override;

  void initialize(const Pose& pose, const InitialSpread& spread) override;
  void initialize_modes(std::span<const Pose> modes, const InitialSpread& spread) override;
  // Through a DevicePoseScorer made on first use (its atlas is separate from the filter's).
  std::vector<double> score_poses(std::span<const Pose> poses, const DepthImage& depth,
                                  const ObservationModel& model) override;
  Estimate update(const DepthImage& depth, double dt) override;
  std::string description() const override;

  // What the last update computed, downloaded for comparison with the reference filter.
  std::vector<double> last_log_likelihoods() const;
  std::vector<int> last_parents() const;
  std::vector<reference::ParticleState> particles() const;
  // The occlusion probabilities and times, particles x pixels (empty where the mode keeps none):
  // downloaded only when asked, for tests.
  std::vector<float> occlusion_state() const;
  std::vector<float> occlusion_times() const;
  // The atlas the last update weighed: particles x pixels depths, tile i = particle i.
  std::vector<float> last_atlas() const;
  // The particles as the last update weighed them (before it resampled).
  std::vector<reference::ParticleState> weighed_particles() const;
  // Replaces the whole filter state (for comparing backends from a common state). occlusion and
  // occlusion_time hold particles x pixels values, or are empty where the mode keeps none.
  void set_state(const std::vector<reference::ParticleState>& particles, const std::vector<float>& occlusion,
                 const std::vector<float>& occlusion_time, const std::vector<double>& log_weights);

 private:
  struct Kernels;
  void render_atlas(StepTimings& timings);
  // The per-particle device memory, checked before anything is allocated.
  size_t checked_particle_count() const;
  void upload_particles(const std::vector<reference::ParticleState>& particles);
  std::vector<reference::ParticleState> unpack(const compute::Buffer<float>& state) const;
  // Enqueues the resampling kernels; their events, for timing.
  std::vector<compute::EventPtr> resample();
  // Enqueues the pose refinement (cl/refine.cl); its event.
  compute::EventPtr refine();
  // Enqueues the shift of the cloud by the refinement's correction, leaving the weighed states in
  // scratch_state_ (where resampling left them, or copied there); its event.
  compute::EventPtr shift_particles();

  std::unique_ptr<compute::Queue> queue_;
  TrackerConfig config_;
  Camera camera_;
  Eigen::Vector3d centre_;
  size_t pixels_, count_;
  std::unique_ptr<AtlasSource> atlas_source_;
  std::unique_ptr<Kernels> kernels_;
  std::unique_ptr<DevicePoseScorer> scorer_;
  Mesh mesh_;  // kept for the scorer, made only when global search runs
  compute::Buffer<float> state_, scratch_state_, log_weight_, log_likelihood_, weights_, cumulative_, estimate_;
  compute::Buffer<unsigned> parents_;
  compute::Buffer<float> atlas_, observed_;
  compute::Buffer<float> occlusion_, occlusion_time_, scratch_occlusion_, scratch_occlusion_time_;
  // The refinement's mesh, one-pose scratch (state, depth bits, triangle ids) and correction twist.
  std::unique_ptr<MeshBuffers> refine_mesh_;
  compute::Buffer<float> refine_pose_, correction_;
  compute::Buffer<unsigned> refine_tile_, refine_ids_;
  bool last_resampled_ = false;
  bool weighed_in_scratch_ = false;  // the last update left the weighed states in scratch_state_
  unsigned frame_ = 0;
  double time_ = 0;
};

}  // namespace depthtrack
