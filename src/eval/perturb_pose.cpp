#include <cmath>
#include <depthtrack/error.hpp>
#include <depthtrack/evaluation.hpp>
#include <numbers>
#include <random>
#include <string>

#include "model/particle.hpp"

namespace depthtrack {

Pose perturb_pose(const Pose& pose, const Eigen::Vector3d& centre, double metres, double degrees, uint64_t seed) {
  if (!std::isfinite(metres) || !std::isfinite(degrees) || !centre.allFinite())
    throw InputError("perturb_pose: the distance (" + std::to_string(metres) + " m), the angle (" +
                     std::to_string(degrees) + " degrees) and the centre must be finite");
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal;
  auto random_unit = [&] {
    Eigen::Vector3d d(normal(rng), normal(rng), normal(rng));
    return Eigen::Vector3d(d.normalized());
  };
  const Eigen::Vector3d direction = random_unit(), axis = random_unit();
  return model::move_about_centre(pose, centre, metres * direction, degrees * std::numbers::pi / 180.0 * axis);
}

}  // namespace depthtrack
