#pragma once
// The whole particle filter, sequential and single-threaded: the readable statement of the method,
// the oracle the device kernels are tested against and the baseline speedups are quoted against.
// With threads > 1 (`--backend cpu`, `cpu:N`) its per-particle loops (propagate, render and weigh,
// resampling's gather of the occlusion rows, pose scoring, the mean pose's terms, the cloud's shift after
// the fit) run in contiguous chunks on a thread pool; every particle's work is independent and the
// reductions (the heaviest particle, the weights' and the mean's sums) run in the sequential order, so
// every result equals the single-threaded one bit for bit. The fit runs on the caller's thread: a
// drawing of it (about 25 us at 80x60) split in bands of rows needs three hand-offs to the pool's
// threads (each about 6 us on a 2-core machine), and drew no faster in wall time.
#include <depthtrack/tracker_config.hpp>
#include <memory>
#include <vector>

#include "core/thread_pool.hpp"
#include "model/filter_backend.hpp"
#include "model/particle.hpp"
#include "model/state_window.hpp"
#include "reference/observation_model.hpp"
#include "reference/pose_refiner.hpp"
#include "reference/pose_score.hpp"
#include "reference/rasterizer.hpp"

namespace depthtrack::reference {

using model::ParticleState;

class ReferenceFilter final : public FilterBackend {
 public:
  ReferenceFilter(const Mesh& mesh, const Camera& camera, const TrackerConfig& config, int threads = 1);

  void initialize(const Pose& pose, const InitialSpread& spread) override;
  void initialize_modes(std::span<const Pose> modes, const InitialSpread& spread) override;
  std::vector<double> score_poses(std::span<const Pose> poses, const DepthImage& depth,
                                  const ObservationModel& model) override;
  std::unique_ptr<PoseScorer> make_pose_scorer(const Mesh& mesh) override;
  Estimate update(const DepthImage& depth, double dt) override;
  std::string description() const override;
  std::pair<int, int> occlusion_window_size() const override { return {window_.width, window_.height}; }
  void set_particle_count(int count) override;
  const std::vector<float>* rendering_of(const Pose& pose) const override { return refiner_.rendering_of(pose); }

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
  // Rows of the state window's pixels (TrackerConfig::occlusion_window), at state_window().
  const std::vector<float>& occlusion_state() const { return occlusion_; }
  const model::StateWindow& state_window() const { return window_; }
  const std::vector<float>& occlusion_times() const { return occlusion_time_; }
  const std::vector<double>& log_weights() const { return log_weights_; }
  // The last frame's fit objective (its last stage's log-likelihood, under the occlusion map the fit used)
  // at any pose: how well another backend's fit did by this one's measure. Draws the pose anew, so
  // rendering_of holds it afterwards.
  double last_fit_objective(const Pose& pose, const DepthImage& depth) const {
    return refiner_.normal_equations(pose, depth, last_fit_occlusion_).objective;
  }
  // Per pose of the last score_poses, the sum of the absolute per-pixel terms.
  const std::vector<double>& last_score_magnitudes() const { return scorer_.last_magnitudes(); }

 private:
  // The occlusion priors of the pixels a particle's Bayes update changed, for the refinement's map.
  struct PixelPrior {
    size_t pixel;
    double p;
  };
  // What one thread needs of its own: the rasterizer (it keeps scratch), a rendering, the priors of
  // the particle being weighed, and its render time this frame.
  struct Lane {
    Rasterizer rasterizer;
    std::vector<float> rendered;
    std::vector<PixelPrior> weighing;
    double render_ms = 0;
  };
  // A chunk's heaviest particle (the first of its equal maxima) and that particle's priors.
  struct ChunkHeaviest {
    bool found = false;
    double log_weight = 0;
    size_t index = 0;
    std::vector<PixelPrior> priors;
  };
  // Calls f(lane, c, first, last) for every chunk c of n items (run_ranges: contiguous, in order, a few
  // a thread), in parallel; lane is the thread's own.
  template <typename F>
  void for_chunks(size_t n, F&& f);

  void propagate(double dt);
  // Renders and weighs particle i on lane; returns its log-likelihood and updates its occlusion state.
  double weigh_particle(size_t i, const DepthImage& depth, double dt, Lane& lane, double& magnitude);
  // Weighs every particle, adds to its log weight and finds the heaviest (the first of equal maxima,
  // as a sequential scan does), whose priors end in priors_; returns it.
  size_t weigh_all(const DepthImage& depth, double dt, Estimate& e);
  void resample(const std::vector<double>& normalized);
  // Every particle and its occlusion rows replaced by parents[child]'s (as many children as parents has).
  void gather(const std::vector<int>& parents);
  // Moves every particle's occlusion rows to next_window_: pixels new to the window start fresh.
  void move_state_window();
  // A fresh pixel's occlusion probability now: occlusion.initial at time 0, aged to time_.
  double fresh_occlusion_now() const;
  // Each pixel's occlusion probability for this frame as particle i held it before this frame's
  // Bayes update (its prior, aged to now); priors_ must hold i's covered pixels.
  std::vector<double> occlusion_map(size_t i) const;
  // Fits the heaviest particle's pose to the likelihood's maximum, reports it in e and shifts every
  // particle by the same correction.
  void refine(Estimate& e, const DepthImage& depth, size_t heaviest);

  TrackerConfig config_;
  Camera camera_;
  Eigen::Vector3d centre_;
  std::vector<Lane> lanes_;  // one per thread; lanes_[0] is the caller's
  std::unique_ptr<ThreadPool> pool_;
  PoseRefiner refiner_;
  std::vector<double> last_fit_occlusion_;  // the occlusion map of the last frame's fit
  ReferencePoseScorer scorer_;
  std::vector<ParticleState> particles_, scratch_particles_;  // scratch: resampling's gather target
  std::vector<double> log_weights_;
  // Occlusion state per particle per pixel: probability, and (per-pixel-time mode) the time of its
  // last update in seconds since the first frame. Stored as float, as a device stores it.
  std::vector<float> occlusion_;
  std::vector<float> occlusion_time_;
  // Where the rows lie (window_), and where the next frame keeps them (centred on the last estimate;
  // an automatic window sized from the object's extent).
  model::ObjectExtent extent_;
  model::StateWindow window_, next_window_;
  size_t state_pixel_limit_;  // the most pixels a window may grow to in the memory (0: no bound)
  std::vector<float> scratch_occlusion_, scratch_occlusion_time_;  // resampling's gather targets
  std::vector<PixelPrior> priors_;                                 // the heaviest particle's
  std::vector<ChunkHeaviest> chunk_heaviest_;                      // weigh_all's, per chunk
  std::vector<ObservedDepth> observed_;  // this frame's, per state window pixel with a valid depth

  std::vector<double> last_log_likelihoods_, last_magnitudes_;
  std::vector<int> last_parents_;
  std::vector<double> last_normalized_;
  unsigned frame_ = 0;
  double time_ = 0;  // seconds since the first frame
};

}  // namespace depthtrack::reference
