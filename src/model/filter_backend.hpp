#pragma once
// What the Tracker asks of an implementation of the particle filter. The reference filter
// (src/reference) is one; the compute-layer filter (src/filter: OpenCL, CUDA) is another. It lives in
// the model layer, which both depend on and which depends on nothing but core. Inputs are already at
// working resolution.
#include <depthtrack/camera.hpp>
#include <depthtrack/depth_image.hpp>
#include <depthtrack/error.hpp>
#include <depthtrack/estimate.hpp>
#include <depthtrack/initial_spread.hpp>
#include <depthtrack/mesh.hpp>
#include <depthtrack/tracker_config.hpp>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "model/pose_scorer.hpp"

namespace depthtrack {

class FilterBackend {
 public:
  virtual ~FilterBackend() = default;
  virtual void initialize(const Pose& pose, const InitialSpread& spread) = 0;
  // Draws the particles around several poses: particle i around modes[i % modes.size()].
  virtual void initialize_modes(std::span<const Pose> modes, const InitialSpread& spread) = 0;
  // Log-likelihood of each pose against depth with the weigh step's per-pixel terms but a fresh
  // occlusion prior (occlusion.initial at every pixel), under `model` (the configuration's own,
  // or a tempered one for a coarse search); reads and writes no filter state. What global search
  // ranks hypotheses by.
  virtual std::vector<double> score_poses(std::span<const Pose> poses, const DepthImage& depth,
                                          const ObservationModel& model) = 0;
  // A scorer of `mesh` (e.g. a simplified copy) on this backend's device, camera and
  // configuration, its programs built now: global search scores through it.
  virtual std::unique_ptr<PoseScorer> make_pose_scorer(const Mesh& mesh) = 0;
  // dt: seconds since the previous frame, 0 for the first frame after initialize(). With refinement the
  // estimate's confidence is the fit's visible share at its pose (the Tracker replaces it by the
  // calibrated confidence of the pose's whole evidence).
  virtual Estimate update(const DepthImage& depth, double dt) = 0;
  // update() in two halves, so that several filters' device work overlaps: enqueue_update starts the
  // frame (a device filter enqueues all of it and waits for nothing; `depth` need not outlive the call)
  // and collect() waits for it and returns its estimate, once per enqueue_update. A host filter runs the
  // whole update in the first half.
  virtual void enqueue_update(const DepthImage& depth, double dt) { pending_ = update(depth, dt); }
  virtual Estimate collect() {
    if (!pending_) throw InputError("filter: collect() without an enqueued update");
    Estimate e = std::move(*pending_);
    pending_.reset();
    return e;
  }
  virtual std::string description() const = 0;
  // The working-resolution depth of the drawn mesh at `pose` when the last update drew exactly that pose
  // (the host filters' refinement, whose last step was kept), else null: the confidence then need not
  // draw it again. Valid until the next update.
  virtual const std::vector<float>* rendering_of(const Pose&) const { return nullptr; }
  // The following updates run with `count` particles, 1 to the configuration's `particles`: the cloud is
  // drawn from its current weights by systematic resampling (its own random stream), every child then
  // weighing the same. The same count is nothing. Every filter here changes its count (the reference's
  // draw); one that does not throws InputError.
  virtual void set_particle_count(int count) {
    throw InputError(description() + " runs a fixed particle count (" + std::to_string(count) +
                     " asked): it cannot change it (set_particle_count, budget_ms)");
  }
  // Width and height of the occlusion state window the last frame kept (TrackerConfig::occlusion_window;
  // 0 x 0 for a filter without one).
  virtual std::pair<int, int> occlusion_window_size() const { return {0, 0}; }

 private:
  std::optional<Estimate> pending_;  // the host filters' estimate between the halves
};

}  // namespace depthtrack
