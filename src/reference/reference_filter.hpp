#pragma once
// The whole particle filter, sequential and single-threaded: the readable statement of the method,
// the oracle the device kernels are tested against and the baseline speedups are quoted against.
#include <depthtrack/tracker_config.hpp>
#include <vector>

#include "filter/filter_backend.hpp"
#include "reference/particle.hpp"
#include "reference/pose_refiner.hpp"
#include "reference/pose_score.hpp"
#include "reference/rasterizer.hpp"

namespace depthtrack::reference {

class ReferenceFilter final : public FilterBackend {
 public:
  ReferenceFilter(const Mesh& mesh, const Camera& camera, const TrackerConfig& config);

  void initialize(const Pose& pose, const InitialSpread& spread) override;
  void initialize_modes(std::span<const Pose> modes, const InitialSpread& spread) override;
  std::vector<double> score_poses(std::span<const Pose> poses, const DepthImage& depth,
                                  const ObservationModel& model) override;
  std::unique_ptr<PoseScorer> make_pose_scorer(const Mesh& mesh) override;
  Estimate update(const DepthImage& depth, double dt) override;
  std::string description() const override { return "reference (sequential CPU)"; }

  // What the last update computed, for comparing backends: per particle, before resampling.
  const std::vector<double>& last_log_likelihoods() const { return last_log_likelihoods_; }
  // Per particle, the sum of the absolute per-pixel terms: the scale against which a float
  // implementation's rounding in that sum is judged (a sum near 0 can cancel terms of +-5).
  const std::vector<double>& last_log_likelihood_magnitudes() const { return last_magnitudes_; }
  // Each particle's parent in the last resampling (identity when it did not resample).
  const std::vector<int>& last_parents() const { return last_parents_; }
  const std::vector<ParticleState>& particles() const { return particles_; }
  // The normalized weights the last resampling drew from, and the particles' stored state.
  const std::vector<double>& last_normalized_weights() const { return last_normalized_; }
  const std::vector<float>& occlusion_state() const { return occlusion_; }
  const std::vector<float>& occlusion_times() const { return occlusion_time_; }
  const std::vector<double>& log_weights() const { return log_weights_; }
  // Per pose of the last score_poses, the sum of the absolute per-pixel terms.
  const std::vector<double>& last_score_magnitudes() const { return scorer_.last_magnitudes(); }

 private:
  void propagate(double dt);
  // Renders and weighs particle i; returns its log-likelihood and updates its occlusion state.
  double weigh_particle(size_t i, const DepthImage& depth, double dt, double& render_ms, double& magnitude);
  void resample(const std::vector<double>& normalized);
  // Each pixel's occlusion probability for this frame as particle i held it before this frame's
  // Bayes update (its prior, aged to now); priors_ must hold i's covered pixels.
  std::vector<double> occlusion_map(size_t i) const;
  // Fits the heaviest particle's pose to the likelihood's maximum, reports it in e and shifts every
  // particle by the same correction.
  void refine(Estimate& e, const DepthImage& depth, size_t heaviest);

  TrackerConfig config_;
  Camera camera_;
  Eigen::Vector3d centre_;
  Rasterizer rasterizer_;
  PoseRefiner refiner_;
  ReferencePoseScorer scorer_;
  std::vector<ParticleState> particles_, scratch_particles_;  // scratch: resampling's gather target
  std::vector<double> log_weights_;
  // Occlusion state per particle per pixel: probability, and (per-pixel-time mode) the time of its
  // last update in seconds since the first frame. Stored as float, as a device stores it.
  std::vector<float> occlusion_;
  std::vector<float> occlusion_time_;
  std::vector<float> scratch_occlusion_, scratch_occlusion_time_;  // resampling's gather targets
  std::vector<float> rendered_;                                    // scratch: one particle's rendering
  // The occlusion priors of the pixels a particle's Bayes update changed: the particle being weighed
  // (weighing_) and the heaviest so far (priors_), for the refinement's occlusion map.
  struct PixelPrior {
    size_t pixel;
    double p;
  };
  std::vector<PixelPrior> weighing_, priors_;
  std::vector<double> last_log_likelihoods_, last_magnitudes_;
  std::vector<int> last_parents_;
  std::vector<double> last_normalized_;
  unsigned frame_ = 0;
  double time_ = 0;  // seconds since the first frame
};

}  // namespace depthtrack::reference
