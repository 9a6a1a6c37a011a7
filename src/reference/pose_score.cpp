#include "reference/pose_score.hpp"

#include <cmath>

#include "model/occlusion_chain.hpp"
#include "reference/observation_model.hpp"

namespace depthtrack::reference {

PoseScore score_pose(const Rasterizer& rasterizer, const TrackerConfig& config, const Pose& pose,
                     const DepthImage& depth, std::span<float> scratch) {
  const PixelBox box = rasterizer.render(pose, scratch);
  const double p = model::fresh_occlusion(config);
  const int width = rasterizer.camera().width;
  PoseScore s;
  for (int v = box.v0; v < box.v1; ++v) {
    for (int u = box.u0; u < box.u1; ++u) {
      const size_t k = static_cast<size_t>(v) * static_cast<size_t>(width) + static_cast<size_t>(u);
      const double y_hat = scratch[k], y = depth.data()[k];
      if (y_hat <= 0 || !DepthImage::is_valid(static_cast<float>(y))) continue;  // adds 0, as in weigh
      const double term = pixel_log_ratio(pixel_densities(config.observation, y, y_hat), p);
      s.log_likelihood += term;
      s.magnitude += std::abs(term);
    }
  }
  return s;
}

ReferencePoseScorer::ReferencePoseScorer(const Mesh& mesh, const Camera& camera, const TrackerConfig& config)
    : config_(config),
      rasterizer_(mesh, camera, config.near_plane, config.observation.max_depth),
      rendered_(static_cast<size_t>(camera.pixel_count())) {}

std::vector<double> ReferencePoseScorer::score(std::span<const Pose> poses, const DepthImage& depth,
                                               const ObservationModel& model) {
  TrackerConfig config = config_;
  config.observation = model;
  std::vector<double> scores(poses.size());
  last_magnitudes_.resize(poses.size());
  for (size_t i = 0; i < poses.size(); ++i) {
    const PoseScore s = score_pose(rasterizer_, config, poses[i], depth, rendered_);
    scores[i] = s.log_likelihood;
    last_magnitudes_[i] = s.magnitude;
  }
  return scores;
}

}  // namespace depthtrack::reference
