#include "reference/pose_mean.hpp"

#include <algorithm>

namespace depthtrack::reference {

Pose weighted_mean_pose(std::span<const Pose> poses, std::span<const double> weights, const Eigen::Vector3d& centre) {
  Eigen::Vector3d mean_centre = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < poses.size(); ++i) mean_centre += weights[i] * poses[i].apply(centre);
  const size_t heaviest = static_cast<size_t>(std::max_element(weights.begin(), weights.end()) - weights.begin());
  Eigen::Quaterniond mean = poses[heaviest].rotation;
  for (int iteration = 0; iteration < 4; ++iteration) {
    Eigen::Vector3d step = Eigen::Vector3d::Zero();
    for (size_t i = 0; i < poses.size(); ++i) step += weights[i] * rotation_log(mean.conjugate() * poses[i].rotation);
    mean = (mean * rotation_exp(step)).normalized();
  }
  return Pose(mean_centre - mean * centre, mean);
}

}  // namespace depthtrack::reference
