#pragma once
// The reported turn of a near-symmetric object (a can, a bowl, a mug) about its axis of symmetry. The
// depth tells that turn little or nothing, so the fit's estimate of it wanders with the pixels' noise
// from frame to frame while the rest of the pose holds: reported as estimated, the object's frame would
// spin at random (docs/covariance.md, "The reported turn about the axis", has the figures). Instead the
// turn alone is filtered: the last report's turn, carried over the frame's time with the motion model's
// angular noise, and this frame's estimate of it are combined in proportion to their variances (a Kalman
// step in one dimension). Where the depth does tell the turn (a mug's handle in view), its variance is
// small and the report follows it; where it does not, the report holds. The rest of the pose is the
// estimate's.
// Which frames can tell it: a mesh symmetric to its last percent (a can, a bowl: SymmetryAxis::share 1)
// shows no part that breaks the symmetry, and the fit's variance of the turn there comes from the mesh's
// and the pixels' noise, not from the object: such a turn is taken as unknown (the report holds) unless
// the share of the seen pixels that breaks the symmetry, (1 - share) times those seen, reaches
// kTellingPixels.
#include <depthtrack/pose.hpp>
#include <depthtrack/tracker_config.hpp>
#include <optional>

#include "core/mesh_symmetry.hpp"

namespace depthtrack {

// The least pixels of the part that breaks the symmetry for a frame to tell the turn: a handful that a
// fit can place (a mug's handle in view shows several times this at 80x60); with fewer, what the fit's
// variance says of the turn comes from the mesh's small departures from its body of revolution and the
// pixels' noise.
constexpr double kTellingPixels = 4.0;

class HeldTurn {
 public:
  HeldTurn(const SymmetryAxis& axis, const MotionModel& motion);

  // The next report is the estimate as it is (a start, a re-seed, a lost frame).
  void reset() { last_.reset(); }

  // The pose to report for this frame's estimate at `time` (s): the estimate turned about the axis
  // (through axis.point, object frame) to the filtered turn. turn_variance: the estimate's variance of
  // that turn (rad^2) from its covariance; +infinity where the depth says nothing of it (the report
  // holds); NaN where there is no covariance (no fit): the estimate is reported and the filter starts
  // again from it. seen_pixels: the pixels where the depth agrees with the estimate (kTellingPixels).
  Pose report(const Pose& estimate, double turn_variance, double seen_pixels, double time);

 private:
  SymmetryAxis axis_;
  double variance_per_second_;  // the motion model's angular noise, rad^2 per second
  std::optional<Pose> last_;    // the last report
  double last_time_ = 0;
  double variance_ = 0;  // of the last report's turn, rad^2
};

// The estimate's variance of a turn about `axis` (unit, camera frame), rad^2, from the rotation block of a
// covariance of the pose's twist about the centre (model/covariance_calibration.hpp's layout): +infinity
// where an axis the turn involves is set apart (+infinity), NaN where the covariance is NaN.
double turn_variance(const Eigen::Matrix<double, 6, 6>& covariance, const Eigen::Vector3d& axis);

}  // namespace depthtrack
