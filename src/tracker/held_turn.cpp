#include "tracker/held_turn.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace depthtrack {

HeldTurn::HeldTurn(const SymmetryAxis& axis, const MotionModel& motion)
    : axis_(axis), variance_per_second_(motion.sigma_angular * motion.sigma_angular * motion.reference_rate) {
  axis_.direction.normalize();
}

Pose HeldTurn::report(const Pose& estimate, double turn_variance, double seen_pixels, double time) {
  if (std::isnan(turn_variance)) {
    last_.reset();
    return estimate;
  }
  if ((1.0 - axis_.share) * seen_pixels < kTellingPixels) turn_variance = std::numeric_limits<double>::infinity();
  if (!last_) {
    last_ = estimate;
    last_time_ = time;
    variance_ = turn_variance;
    return estimate;
  }
  const double prior = variance_ + variance_per_second_ * std::max(0.0, time - last_time_);
  // The share of the estimate's turn that the report takes: none where the estimate knows nothing of it,
  // all of it where the last report knew nothing.
  double gain = 0;
  if (std::isinf(turn_variance)) {
    // nothing from the estimate: the report holds
  } else if (std::isinf(prior)) {
    gain = 1;
  } else if (prior + turn_variance > 0) {
    gain = std::clamp(prior / (prior + turn_variance), 0.0, 1.0);
  }

  // The estimate as the last report turned by some swing, then by `turn` about the axis (object frame):
  // estimate.rotation = last.rotation * swing * twist(turn). Only the twist is filtered.
  Eigen::Quaterniond relative = (last_->rotation.conjugate() * estimate.rotation).normalized();
  if (relative.w() < 0) relative.coeffs() = -relative.coeffs();  // the same rotation, its turn in [-pi, pi]
  const Eigen::Vector3d& d = axis_.direction;
  const double turn = 2.0 * std::atan2(relative.vec().dot(d), relative.w());
  // The report turns the estimate back by what it does not take, about the axis through axis.point:
  // x -> p + R (x - p) in the object frame.
  const Eigen::Quaterniond back(Eigen::AngleAxisd(gain * turn - turn, d));
  const Pose reported = estimate * Pose(axis_.point - back * axis_.point, back);

  last_ = reported;
  last_time_ = time;
  variance_ = gain == 1 ? turn_variance : (1.0 - gain) * prior;  // (an unknown prior stays unknown at gain 0)
  return reported;
}

double turn_variance(const Eigen::Matrix<double, 6, 6>& covariance, const Eigen::Vector3d& axis) {
  const Eigen::Matrix3d block = covariance.block<3, 3>(3, 3);
  if (block.array().isNaN().any()) return std::numeric_limits<double>::quiet_NaN();
  double variance = 0;
  for (int i = 0; i < 3; ++i) {
    if (axis[i] == 0) continue;
    if (std::isinf(block(i, i))) return std::numeric_limits<double>::infinity();
    for (int j = 0; j < 3; ++j)
      if (axis[j] != 0 && std::isfinite(block(i, j))) variance += axis[i] * axis[j] * block(i, j);
  }
  return variance;
}

}  // namespace depthtrack
