#pragma once
// The likelihood of a pose on its own: the per-pixel terms weigh() sums, with every pixel's
// occlusion probability at the fresh prior. What global search ranks hypotheses by.
#include <depthtrack/depth_image.hpp>
#include <depthtrack/tracker_config.hpp>
#include <span>

#include "reference/rasterizer.hpp"

namespace depthtrack::reference {

struct PoseScore {
  double log_likelihood = 0;  // sum over covered pixels with valid depth of log(mixture / p_bg)
  double magnitude = 0;       // sum of the terms' absolute values (scale for float comparisons)
};

// Renders pose into scratch (camera pixels) and sums its terms against depth.
PoseScore score_pose(const Rasterizer& rasterizer, const TrackerConfig& config, const Pose& pose,
                     const DepthImage& depth, std::span<float> scratch);

}  // namespace depthtrack::reference
