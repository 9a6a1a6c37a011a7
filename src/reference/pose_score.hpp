#pragma once
// The likelihood of a pose on its own: the per-pixel terms weigh() sums, with every pixel's
// occlusion probability at the fresh prior. What global search ranks hypotheses by.
#include <depthtrack/depth_image.hpp>
#include <depthtrack/tracker_config.hpp>
#include <span>

#include "model/pose_scorer.hpp"
#include "reference/rasterizer.hpp"

namespace depthtrack::reference {

struct PoseScore {
  double log_likelihood = 0;  // sum over covered pixels with valid depth of log(mixture / p_bg)
  double magnitude = 0;       // sum of the terms' absolute values (scale for float comparisons)
};

// Renders pose into scratch (camera pixels) and sums its terms against depth.
PoseScore score_pose(const Rasterizer& rasterizer, const TrackerConfig& config, const Pose& pose,
                     const DepthImage& depth, std::span<float> scratch);

// score_pose for each pose, with its own rasterizer of the mesh it was made with.
class ReferencePoseScorer final : public PoseScorer {
 public:
  ReferencePoseScorer(const Mesh& mesh, const Camera& camera, const TrackerConfig& config);
  std::vector<double> score(std::span<const Pose> poses, const DepthImage& depth,
                            const ObservationModel& model) override;
  // Per pose of the last score(), the sum of the absolute per-pixel terms.
  const std::vector<double>& last_magnitudes() const { return last_magnitudes_; }

 private:
  TrackerConfig config_;
  Rasterizer rasterizer_;
  std::vector<float> rendered_;
  std::vector<double> last_magnitudes_;
};

}  // namespace depthtrack::reference
