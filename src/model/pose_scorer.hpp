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
};

}  // namespace depthtrack
