#pragma once
// Scores pose hypotheses against one frame, for global search: the weigh step's per-pixel terms
// with a fresh occlusion prior, no filter state read or written. A backend makes one per mesh
// (FilterBackend::make_pose_scorer) on its own device, with its programs built when it is made.
#include <depthtrack/depth_image.hpp>
#include <depthtrack/pose.hpp>
#include <depthtrack/tracker_config.hpp>
#include <span>
#include <vector>

namespace depthtrack {

class PoseScorer {
 public:
  virtual ~PoseScorer() = default;
  // One log-likelihood per pose, in order, under `model` (the tracker's own or a tempered one).
  virtual std::vector<double> score(std::span<const Pose> poses, const DepthImage& depth,
                                    const ObservationModel& model) = 0;
  // Where the scorer computes them on its device: each pose's visible box over its mesh's vertices, as
  // search::visible_box defines it (a vertex hidden by a depth nearer by more than pixel_sigmas sigma(y)
  // of model), 4 values per pose (u0, v0, u1, v1 in the depth's pixels; u1 < u0 where none is visible).
  // Empty where it does not: the caller computes them on the host.
  virtual std::vector<float> visible_boxes(std::span<const Pose> /*poses*/, const DepthImage& /*depth*/,
                                           const ObservationModel& /*model*/, double /*pixel_sigmas*/) {
    return {};
  }
};

}  // namespace depthtrack
